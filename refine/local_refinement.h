// refine/local_refinement.h: the local refinement of Cheng & Shi 2004 §4.3 —
// edge flips towards the restricted Delaunay triangulation, edge contraction
// for [L], vertex insertion at surface Delaunay centres for [U] — on a mesh
// whose vertices lie on the skin.
// Notes: papers/refine/local_refinement.md
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "geometry/mesh/surface_mesh.h"
#include "skin/run_context.h"
#include "skin/skin_surface.h"

namespace skinmesh::refine {

/// The operations of the local refinement an observer is told about
/// (Cheng & Shi §4.3): an edge flip towards the restricted Delaunay
/// triangulation, an edge contraction for [L], a vertex insertion for [U].
enum class RefineOperation : unsigned char { Flip, Contraction, Insertion };

/// Lower-case name of an operation ("flip", "contraction", "insertion").
const char* operation_name(RefineOperation op);

/// Options of the local refinement.
struct RefineOptions {
  /// At most this many rounds of (contraction pass, insertion pass). A guard
  /// only: the number of rounds that change something is bounded by the
  /// number of contractions and insertions, both finite
  /// (papers/refine/local_refinement.md, "Termination").
  int max_rounds = 60;
  /// Flips per Lawson pass are capped at this factor times the number of edges
  /// (termination of flips with surface Delaunay balls is not proved,
  /// papers/front/open_questions.md Q9.2 (the flip criterion)); passes that hit the cap are counted
  /// in RefineStats::flip_caps.
  double max_flips_factor = 20;
  /// An insertion is refused when a vertex inserted earlier lies closer than
  /// min_inserted_separation · R to the new point (R: the surface Delaunay
  /// radius of the violating triangle). With the value above 0.921 (derived
  /// from C, Q and the 1-Lipschitz rho in papers/refine/local_refinement.md,
  /// "Termination"), no edge between two inserted vertices can violate [L],
  /// and the inserted vertices are separated by a fixed fraction of rho, so
  /// there are finitely many of them.
  double min_inserted_separation = 0.93;
  /// An insertion is refused when the new point would lie closer than
  /// min_insertion_clearance · R to a corner of the triangle that contains it
  /// (R: the surface Delaunay radius of the violating triangle): its ball is
  /// far from empty, a flip will fix the triangle instead. [measured]
  double min_insertion_clearance = 0.25;
  /// A new point whose smallest barycentric coordinate in its containing
  /// triangle is below this splits the opposite edge instead of the
  /// triangle (no sliver next to the edge). [measured]
  double split_edge_barycentric = 0.15;
  /// Called after every flip, contraction and insertion with the mesh as it
  /// is then (a contraction or insertion is told before the flips that
  /// follow it); empty: not called. For recorders (trace/trace_recorder.h);
  /// the mesh must not be changed, and the refinement does the same with or
  /// without an observer.
  std::function<void(RefineOperation, const geometry::SurfaceMesh&)> observer;
};

/// What the refinement did and what it left.
struct RefineStats {
  std::size_t flips = 0, contractions = 0, insertions = 0;
  std::size_t rounds = 0;
  /// Operations wanted but refused because they would turn a triangle over
  /// (against the skin normal) or break the link condition.
  std::size_t refused_contractions = 0, refused_insertions = 0;
  /// Insertions refused because an earlier inserted vertex lies within
  /// min_inserted_separation · R (also counted in refused_insertions), and
  /// contractions of an [L] edge refused because the vertex they would delete
  /// was inserted by the refinement (also counted in refused_contractions).
  std::size_t crowded_insertions = 0, protected_contractions = 0;
  /// Lawson passes stopped by the max_flips_factor cap.
  std::size_t flip_caps = 0;
  /// Violations left when the refinement stopped (0 and 0 when it converged).
  std::size_t L_left = 0, U_left = 0;
};

/// Adds the counts of b to a (rounds: the larger): the refinement of several
/// meshes (the parts of mesher/, the regions of decompose/) as one.
void add_refine_stats(RefineStats& a, const RefineStats& b);

/// Refines a triangle mesh of the skin in place so that every edge
/// satisfies [L], every triangle [U] and (as far as flips reach) every edge is
/// locally restricted Delaunay: Lawson flips with the surface Delaunay ball
/// test (papers/front/open_questions.md Q9.2 (the flip criterion)), then rounds of contraction of
/// edges that violate [L] (keeping the endpoint whose new star has the better
/// minimum angle, Q9.3 (contraction for [L])) and insertion of the surface Delaunay centre of
/// triangles that violate [U] (Q9.4 (insertion for [U])), each followed by local flips. [L] and [U] together
/// bound every angle below by arcsin(1/Q²) = 21.55°.
///
/// `mesh` must be oriented outwards, with every vertex on the skin, and
/// closed or open with its boundary kept: a boundary vertex is never
/// deleted, a boundary edge never flipped or split, and an insertion whose
/// walk reaches the boundary is refused (a region of decompose/, refined
/// before the glue; the pass over the glued mesh repairs its seams);
/// it uses (and creates if absent, sampling the skin) the vertex property
/// skin::kVertexCell (mixed cell), from which it takes the normal and rho
/// (skin::VertexNormals, skin::VertexRhos), sets it on the vertices it
/// inserts, and sets skin::kVertexInserted (1 on the vertices it inserted)
/// (skin/vertex_data.h). C and Q come from run.size; the scans that read
/// every element (the first Lawson pass's suspects, the first [L] and [U]
/// scans) run on run.threads threads, and the refinement is the same for
/// every count (core/parallel.h).
/// No operation turns a triangle against the normals of its corners, no vertex
/// moves, and a vertex inserted here is never deleted; the number of
/// operations is finite (papers/refine/local_refinement.md, "Termination").
/// Elements are deleted, not compacted: call garbage_collection() afterwards.
RefineStats refine_mesh(const skin::SkinSurface& skin, geometry::SurfaceMesh& mesh, const RefineOptions& opt = {},
                        const skin::RunContext& run = {});

/// refine_mesh() on a mesh whose elements are refined already except near
/// `seeds` (faces of `mesh`): the regions of decompose/, each refined with
/// its boundary kept, glued by bands whose triangles and the triangles around
/// their corners are the seeds. The Lawson pass starts from the seeds' edges
/// only, the first [L] and [U] scans test the seeds' edges and faces, and
/// the rounds end with one scan of every element (on run.threads threads),
/// whose violators are taken up as refine_mesh() would: [L] and [U] hold on
/// the whole mesh as far as refine_mesh() makes them hold. Edges away from
/// the seeds and from every change are not tested for the restricted
/// Delaunay property (the regions' pass flipped them). Same preconditions,
/// stats and errors as refine_mesh().
RefineStats refine_seams(const skin::SkinSurface& skin, geometry::SurfaceMesh& mesh,
                         const std::vector<geometry::Face>& seeds, const RefineOptions& opt = {},
                         const skin::RunContext& run = {});

}  // namespace skinmesh::refine

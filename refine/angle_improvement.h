// refine/angle_improvement.h: vertex moves after the local refinement that
// raise the smallest angles and keep [L], [U], the restricted Delaunay property
// and the embedding. Not in Cheng & Shi 2004 (§2.2: [L] and [U] bound the
// angles by 21.55° only). Notes: papers/refine/angle_improvement.md
#pragma once

#include <cstddef>

#include "geometry/mesh/surface_mesh.h"
#include "skin/run_context.h"
#include "skin/skin_surface.h"

namespace skinmesh::refine {

/// Options of the angle-improvement pass.
struct AngleImprovementOptions {
  /// Vertices of a triangle with an angle below this (degrees) are moved.
  /// [measured: 28° selects about 0.05 % of the triangles of the bundled
  /// molecules and lifts their minimum angle to 26.0°–28.7° for 1–5 % of the
  /// meshing time; 30° costs 14 % (papers/refine/angle_improvement.md)]
  double target_angle_deg = 28;
  /// At most this many passes; a pass tries every vertex of a star below
  /// the target once, the next one the moved vertices and their rings.
  /// [measured: the bundled molecules need 1–4]
  int max_passes = 4;
  /// At most this many steps of the max-min ascent per vertex. [measured:
  /// the ascent stops after 4 steps on average]
  int max_ascent_steps = 12;
  /// A vertex moves at most this fraction of its shortest star edge (in its
  /// tangent plane, before the projection onto the skin). [measured: 0.25,
  /// 0.4 and 0.6 give the same minimum angles on the bundled molecules; 0.25
  /// has the fewest refused positions, e.g. 142, 212, 256 on A-DNA at probe 0]
  double max_move_factor = 0.25;
  /// Relative margin of the restricted Delaunay tests (1e-7): a move is
  /// refused unless every vertex that must lie outside a surface Delaunay
  /// ball is farther than (1 + ball_margin) times its radius from its
  /// centre, 100 times the verifier's tolerance (1e-9), so that the
  /// verifier's own evaluation of the same balls cannot disagree.
  double ball_margin = 1e-7;
};

/// What the pass did.
struct AngleImprovementStats {
  /// Triangles with an angle below the target when the pass started.
  std::size_t low_triangles = 0;
  std::size_t passes = 0;
  /// Vertices whose star was optimised (at most once per pass), and those
  /// that moved.
  std::size_t attempts = 0, moves = 0;
  /// Attempts that found positions with a better star, none of them
  /// admissible.
  std::size_t refused = 0;
  /// Improving positions refused by the final check, by the first condition
  /// they broke: a star triangle turned against a corner normal, a surface
  /// Delaunay ball holding a vertex (or missing), a star triangle meeting
  /// another triangle.
  std::size_t refused_orientation = 0, refused_rdt = 0, refused_intersection = 0;
  /// Attempts whose ascent found no better position and whose last refused
  /// step broke [L] (resp. [U]): the ascent keeps both conditions.
  std::size_t refused_L = 0, refused_U = 0;
  /// True if the pass did nothing because a triangle's circumradius exceeds
  /// 0.2 rho_min (so far beyond [U] that the neighbourhood bounds of
  /// papers/refine/angle_improvement.md do not hold).
  bool skipped = false;
  /// Smallest angle of the mesh (degrees) before and after the pass.
  double min_angle_before_deg = 0, min_angle_after_deg = 0;
  /// The bound kappa on circumradius / rho_min that sizes every move's
  /// neighbourhood (papers/refine/angle_improvement.md): the largest ratio
  /// over the mesh (padded), at least C·Q. A move's search radius grows with
  /// it, so one poor triangle makes every move of its mesh look further.
  double kappa = 0;
};

/// Raises the smallest angles of a closed mesh of the skin in place by
/// moving vertices: every vertex of a triangle with an angle below
/// opt.target_angle_deg is moved in its tangent plane by a max-min-angle
/// ascent over its star (Freitag et al. 1995 style: along the min-norm
/// element of the convex hull of the active angles' gradients), each trial
/// position projected onto the skin along the vertex normal
/// (skin::SkinSurface::project_along_line, papers/skin/skin_math.md §7.2).
/// The best position (failing it, an earlier point of the ascent, the ring's
/// centroid, or a shorter move along the best one) is accepted only if the
/// star's minimum angle strictly increases and: every
/// star triangle faces along the skin normals of its three corners, every
/// star edge satisfies [L] and every star triangle [U] (with rho at the new
/// position), every star triangle's surface Delaunay ball exists and holds no
/// other vertex, the new position lies in no other triangle's surface
/// Delaunay ball, and no star triangle meets another triangle (exact test).
/// The balls and triangles that could be affected are found by brute force
/// in a neighbourhood whose radius follows from the triangles' largest
/// R / rho_min (below CQ under [U]) and the 1-Lipschitz rho, through a grid
/// of all vertices (papers/refine/angle_improvement.md, "Which triangles a
/// move can affect"), not only in the one-ring. Connectivity never changes.
/// Positions in Å, angles of the options and statistics in degrees.
///
/// `mesh` must be closed, oriented outwards, with every vertex on the skin;
/// it uses the vertex property skin::kVertexCell of the refinement
/// (refine_mesh; sampled from the skin where absent), from which it takes the
/// normal and rho (skin::VertexNormals, skin::VertexRhos), and keeps it up to
/// date for the moved vertices. Meant to
/// run after refine_mesh(): a vertex whose star breaks one of the conditions
/// already is not moved (every condition is required after the move), so the
/// pass never adds a violation; C and Q of [L] and [U] come from run.size.
/// Deterministic (no hashing order): the scans of every triangle run on
/// run.threads threads and give the same lists for every count
/// (core/parallel.h); the moves are made one at a time, in order.
/// Throws nothing but std::bad_alloc and GeometryError from point location.
AngleImprovementStats improve_angles(const skin::SkinSurface& skin, geometry::SurfaceMesh& mesh,
                                     const AngleImprovementOptions& opt = {}, const skin::RunContext& run = {});

}  // namespace skinmesh::refine

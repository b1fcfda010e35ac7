// front/sweep.h: the adaptive sweeping triangulation — an advancing front that
// grows from the minima of the height function upwards, bridges at saddles and
// seals at maxima, with triangle sizes adapted to the local length scale rho.
// Cheng & Shi 2004 §4.1 (Algorithm 1: creation, creep, wing, bridge, seal) and
// §4.2 (tangent-disc radius). The local refinement of §4.3 is a separate stage
// (refine/local_refinement.h), run after the sweep by the pipeline
// (mesher/pipeline.h).
// Notes: papers/front/README.md (one note per operation).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "geometry/mesh/surface_mesh.h"
#include "morse/morse_smale_complex.h"
#include "skin/run_context.h"
#include "skin/skin_surface.h"

namespace skinmesh::front {

struct SweepStats;

/// The operations of the sweep an observer is told about: Algorithm 1's
/// creation (a bowl at a minimum, Figure 5), creep (a fan at the lowest front
/// vertex, Figure 6; it may end in a contact, which joins two front parts),
/// wings (Figure 7), hold (a front vertex stops in a protecting sphere),
/// bridge (Figure 8) and seal (a hole closed at the end), and the project's
/// small hole (a hole closed during the sweep, papers/front/hole_filling.md)
/// and patch (a tangled region re-meshed by the fallback, papers/front/patch.md).
enum class SweepOperation : unsigned char { Creation, Creep, Wings, Hold, Bridge, SmallHole, Seal, Patch };

/// Lower-case name of an operation ("creation", "creep", "wings", "hold",
/// "bridge", "small hole", "seal", "patch").
const char* operation_name(SweepOperation op);

/// One operation of the sweep as an observer sees it, right after it ran
/// (SweepOptions::observer). The references are valid during the call only.
struct SweepEvent {
  SweepOperation op = SweepOperation::Creep;
  /// The departure vertex (creep, wings after a creep, hold, small hole);
  /// invalid otherwise.
  geometry::Vertex vertex;
  /// The critical point (creation: the minimum; hold and bridge: the
  /// protecting sphere's critical point); kInvalidIndex otherwise.
  Index critical = kInvalidIndex;
  /// Faces with an index >= first_face were added by the operation (some may
  /// be marked deleted again); faces below it may have been deleted by it
  /// (a re-opened or enlarged hole).
  std::size_t first_face = 0;
  /// The partial mesh after the operation; its boundary is the front.
  const geometry::SurfaceMesh& mesh;
  /// The sweep's counters after the operation (a creep that joined two front
  /// parts raised `contacts`).
  const SweepStats& stats;
};

/// Every tuning number of the sweep, with its meaning, unit and the origin of
/// its default: [paper] Cheng & Shi 2004, [derived] a derivation in papers/,
/// [measured] chosen by experiment on the bundled molecules and the stress
/// inputs (papers/front/*.md say which). Lengths are multiples of the
/// tangent-disc radius r = disc_factor · rho(v) of the vertex concerned.
struct SweepOptions {
  // From the paper (Cheng & Shi 2004 §2.2, §4.1).
  /// Angle of one fan triangle at its apex (degrees): a bowl has 360/60 = 6
  /// triangles, a creep fan ceil(theta / 60°). [paper §4.1]
  double fan_angle_deg = 60;
  /// wing() closes a front angle below this (degrees). [paper §4.1: "no
  /// angles smaller than 90° between any two adjacent front edges"]
  double wing_angle_deg = 90;

  // Derived from the paper (papers/skin/skin_math.md §8).
  /// Tangent-disc radius r_a = disc_factor · rho(a) (Cheng & Shi §4.2). Must lie
  /// in size's window (disc_factor_lower(), disc_factor_upper()] =
  /// (0.1074, 0.2077] for the default C, Q. [derived] 0.185: below 0.1853 the
  /// fan triangles satisfy [U] themselves (papers/skin/skin_math.md §8).
  double disc_factor = 0.185;

  // Measured: the creep's and the bridge's safeguards (papers/front/creep.md, wing.md, bridge.md).
  /// A forced wing (a neighbour over which a fan would fold) closes angles
  /// below this (degrees): any convex corner. [measured]
  double forced_wing_angle_deg = 180;
  /// A wing's new edge u-w may be at most this times the larger disc radius
  /// r of u and w: forced wings chained along a front next to a held vertex
  /// would otherwise join it to ever farther vertices (gramicidin A at probe
  /// 0 grew such an edge to 3.7 r, and its hole could not be sealed).
  /// [measured]
  double wing_max_edge_factor = 2.0;
  /// Rounds of "wing a neighbour, recompute the fan" in one creep. [measured]
  int max_wing_rounds = 8;
  /// A new fan point closer than fan_clearance · r to the neighbour's other
  /// front neighbour makes that neighbour a wing candidate. [measured]
  double fan_clearance = 0.5;
  /// A creep whose fan would fold is postponed at most this many times.
  /// [measured]
  int max_deferrals = 8;
  /// Each deferral re-queues the vertex defer_step · r · (deferrals so far)
  /// higher. [measured]
  double defer_step = 0.25;
  /// The tangent angles at a vertex plus its hole angle must make 360° within
  /// this (degrees), else the mesh folds. [measured: numerical noise is
  /// below 1e-6°; a fold thinner than this goes unnoticed here and is
  /// caught by the final self-intersection check]
  double fold_tolerance_deg = 5;
  /// After a bridge, free front vertices within bridge_requeue_factor · r_p
  /// of the saddle are queued again (r_p: its protecting radius). [measured]
  double bridge_requeue_factor = 3;

  // Measured: the collision safety net, not in the paper (papers/front/collision_net.md).
  /// A fan point within collision_radius · r of another vertex would come too
  /// close to another front part. [measured]
  double collision_radius = 0.5;
  /// Vertices whose normals make a larger angle than acos(min_normal_cosine)
  /// are on another sheet of the skin and never collide or touch. [measured]
  double min_normal_cosine = 0.5;
  /// A free front vertex within contact_radius · r of the departure vertex,
  /// in each other's hole wedge, is joined to it by a contact. [measured]
  double contact_radius = 1.5;
  /// Contact candidates must lie this far (degrees) inside both hole wedges.
  /// [measured]
  double contact_margin_deg = 15;
  /// Front vertices fewer than this many hops away along the front are left
  /// to wing() instead of a contact. [measured]
  int contact_min_hops = 3;

  // Measured: small holes and the seal's hole filling, not in the paper (papers/front/seal.md, hole_filling.md).
  /// A front loop of at most small_hole_vertices vertices, all within
  /// small_hole_reach · r of the departure vertex, is a small hole, closed
  /// at once. [measured]
  int small_hole_vertices = 7;
  /// See small_hole_vertices. [measured]
  double small_hole_reach = 2.5;
  /// Holes of at most this many vertices are filled by the max-min-angle
  /// dynamic programme (O(k³)); larger ones by ear clipping. [measured]
  int dp_max_hole_vertices = 40;
  /// A projection plane for ear clipping must make an angle below
  /// acos(seal_plane_min_cosine) with the hole's average normal. [measured]
  double seal_plane_min_cosine = 0.3;
  /// A hole tangled in every projection is enlarged (its faces deleted) at
  /// most this many times. [measured]
  int max_hole_enlargements = 2;
  /// A small hole tangled in every projection during the sweep (or a fold at
  /// a departure vertex) is re-opened: the faces around it deleted, their
  /// corners back on the front. A region is re-opened only if none of its
  /// corners has been on the rim of this many re-opened regions already: the
  /// sweep is deterministic, so a region re-meshed from the same rim tangles
  /// the same way again, and then goes to the seal and the fallback instead.
  /// [derived] 1 (papers/front/hole_filling.md, "Re-opening").
  int max_reopenings = 1;
  /// A vertex departs at most this many times (a departure: a valid entry
  /// taken from the queue, whatever it then does); one more and it is left
  /// for the seal. With the cap on re-opened faces this bounds the departures
  /// by the size of the swept mesh (departure_bound()). [measured] far above
  /// what any input needs (papers/front/sweep.md, "Progress").
  int max_departures = 32;
  /// Rounds of deleting the faces at pinched vertices while enlarging a hole.
  /// [measured]
  int max_pinch_rounds = 4;

  // The fallback where the front tangles, not in the paper (papers/front/patch.md).
  /// A hole that the seal cannot close (tangled in every plane after its
  /// enlargements, or without an ear), and a small hole met during the sweep
  /// that cannot be re-opened (left open for the seal), are re-meshed: the
  /// faces of a region around them are replaced by the restricted Delaunay
  /// triangulation of a sample of the skin conforming to the region's
  /// boundary, the region growing until that patch is valid. False: such a
  /// hole stops the sweep with TopologyError (the tests of the fallback
  /// compare both).
  bool patch_fallback = true;
  /// Testing aid for the fallback: the fold checks of creep() with these
  /// ordinal numbers (0 = the first fold check of the sweep) report a fold
  /// as if the mesh folded at the departure vertex. Empty in every real run.
  std::vector<std::size_t> injected_folds;
  /// Testing aid for the fallback: if N > 0, every N-th hole the seal meets
  /// (the first, the (N+1)-th, …; the small holes of the sweep not counted)
  /// goes straight to the patch, as if every way of closing it had failed; a
  /// hole whose patch fails is traced ("patch: forced patch failed") and then
  /// sealed as usual. 0 in every real run.
  std::size_t force_patch_every = 0;

  // Reporting and debugging aids (papers/front/sweep.md, "Debugging aids").
  /// After every operation, check that the tangent angles around the vertices
  /// of the new triangles make 360° (no fold); throw TopologyError naming the
  /// operation otherwise.
  bool paranoid = false;
  /// Called with one line per decision of the sweep (creep, wing refusals,
  /// contacts, bridges, seals, the vertices of a hole that cannot be sealed);
  /// empty: no trace.
  std::function<void(const std::string& line)> trace;
  /// Called after every operation (creation, creep, wings, hold, bridge, small
  /// hole, seal) with the partial mesh; empty: not called. For recorders of
  /// the sweep (tests/mesher/sweep_test.cpp replays it); it must not throw
  /// unless the sweep is to stop.
  std::function<void(const SweepEvent&)> observer;
  /// Stop with TopologyError after this many departures (valid queue entries;
  /// negative: no limit).
  long max_steps = -1;
  /// If not empty, the partial mesh is written here before the seal, when a
  /// paranoid check fails, and when max_steps stops the sweep (a geometric
  /// format of geometry::write_mesh: .ply, .off, .obj, .stl or .vtk).
  std::string dump_path;
};

/// Counters of the sweep (Algorithm 1's operations and the safety net).
struct SweepStats {
  std::size_t creations = 0, creeps = 0, wings = 0, bridges = 0;
  std::size_t seals = 0;  ///< holes closed: at the seal and small holes during the sweep
  std::size_t held =
      0;  ///< vertices held: in a protecting sphere, or next to a held vertex they would fold over or touch
  std::size_t deferred = 0;        ///< creeps postponed because the fan would fold (Figure 7)
  std::size_t bridge_rows = 0;     ///< ladder rows added by bridges
  std::size_t contacts = 0;        ///< front parts joined by the safety net (not in the paper)
  std::size_t stuck = 0;           ///< departure vertices left for the seal (no fan fits, Figure 7)
  std::size_t enlarged_holes = 0;  ///< tangled holes at the seal enlarged by deleting the faces around them
  std::size_t reopened_holes = 0;  ///< tangled small holes during the sweep whose region went back to the front
  std::size_t collisions = 0;      ///< fans that would have come within collision_radius · r of another vertex
  /// Wings and one-triangle fans refused because their triangle would cover a
  /// front vertex of another front part (covered_front_vertex).
  std::size_t covered_triangles = 0;
  std::size_t released = 0;       ///< saddles whose holds were released unbridged
  std::size_t merged_minima = 0;  ///< minima left without a bowl: it would have overlapped a neighbouring bowl
  /// Openings the sweep left for the seal (fallback): tangled small holes that
  /// could not be re-opened, folds at a departure vertex, fans that would
  /// have covered meshed surface.
  std::size_t left_holes = 0;
  /// Folds met at a departure vertex and taken by the fallback: the faces
  /// around it re-opened, or the vertex left for the seal (left_holes).
  std::size_t folds = 0;
  std::size_t patched_holes = 0;  ///< holes whose region the fallback re-meshed (papers/front/patch.md)
  std::size_t patch_faces = 0;    ///< faces the fallback's patches added
  /// Departure vertices parked below a region's upper cut (front/region.h); 0
  /// for the whole skin.
  std::size_t parked = 0;
  /// Departures: valid entries taken from the queue (Algorithm 1, line 2).
  std::size_t departures = 0;
  /// Vertices left for the seal because they had departed max_departures
  /// times (the progress guarantee; 0 on every input met so far).
  std::size_t spent_vertices = 0;
  /// The most departures of one vertex (at most max_departures).
  std::size_t most_departures = 0;
  /// Faces deleted by re-opened regions (never more than the faces left).
  std::size_t reopened_faces = 0;
  /// Faces of the partial mesh when the departures ended (before the seal).
  std::size_t swept_faces = 0;
};

/// The progress guarantee (papers/front/sweep.md, "Progress"): an upper
/// bound on `s.departures` for a sweep run with `max_departures`
/// (SweepOptions), from its size alone: with F = s.swept_faces and B =
/// max_departures, (B + 1) (7 s.creations + 2 F) + 7 F. Holds for a sweep and,
/// the bound being linear, for the sums of add_stats.
std::size_t departure_bound(const SweepStats& s, int max_departures);

/// The closed mesh produced by the sweep, before the local refinement.
struct SweepResult {
  /// Closed triangle mesh of the skin, faces counter-clockwise about the
  /// outward normal, every vertex on the skin. Elements may be marked deleted
  /// (call garbage_collection()). Vertex property (skin/vertex_data.h):
  /// skin::kVertexCell (mixed cell), which gives the unit outward skin normal
  /// and the local length scale rho (Å) at the vertex (skin::VertexNormals,
  /// skin::VertexRhos).
  geometry::SurfaceMesh mesh;
  SweepStats stats;
};

/// Meshes the skin by Algorithm 1 of Cheng & Shi §4.1: creation at every live
/// minimum of `ms`, creeps from the lowest front vertex, holds in protecting
/// spheres, bridges at saddles, seals at maxima. `ms` gives the critical
/// points (live ones after simplification), their protecting spheres and the
/// height direction. C and Q come from `run`, which also gets the progress
/// ("sweep" and the fraction of the height range swept). Throws
/// std::invalid_argument if opt.disc_factor is outside the tangent-disc
/// window of run.size, TopologyError when the front
/// cannot be closed consistently (a fold, a hole without an ear), GeometryError
/// when a projection fails.
SweepResult sweep_mesh(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const SweepOptions& opt = {},
                       const skin::RunContext& run = {});

}  // namespace skinmesh::front

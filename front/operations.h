// front/operations.h: Algorithm 1 of Cheng & Shi 2004 §4.1 as free functions
// over the sweep's state (front/front_state.h), in the paper's order —
// creation (Figure 5), creep (Figure 6, its plan by Figure 7), wing
// (Figure 7), bridge (Figure 8), seal — then the driver of the loop, then
// what the paper does not have: the contact search, the fan-collision net,
// small holes, the max-min-angle hole filling and the re-opening of tangled
// holes, and the front's geometry in tangent planes. Each function is defined
// in the file named beside it. A function that takes `const FrontState&`
// reads the state only.
// Only front/*.cpp and the unit tests of tests/front include this header.
// Notes: papers/front/README.md (one note per operation)
#pragma once

#include <cstddef>
#include <vector>

#include "front/front_state.h"

namespace skinmesh::front::detail {

// ---------------------------------------------------------------------------
// Algorithm 1's operations (Cheng & Shi §4.1, §4.2)

/// creation() at minimum c: a bowl of six triangles around it (creation.cpp,
/// Figure 5).
void creation(FrontState& fs, Index c);

/// What creep() at a departure vertex will do, decided before any triangle is
/// built (creep.cpp; Figure 7's test and the project's safeguards).
enum class CreepVerdict {
  Build,      ///< build the fan of `triangles` triangles (Figure 6)
  Wing,       ///< the front angle at v is below 90°: v was winged instead (Figure 7)
  Contact,    ///< v's front was joined to a nearby part of the front (try_contact)
  Hold,       ///< v joins the hold of a neighbouring held vertex
  Defer,      ///< v is re-queued a little higher, so that the front moves on around it
  Stuck,      ///< no fan fits: v is left for the seal
  Collision,  ///< the fan would come too close to another vertex: v was held, joined, deferred or left for the seal
  Reopened,   ///< the mesh folds at v: the faces around it went back to the front (fallback)
};

/// The plan of a creep at v: the verdict, the corner of the front at v, the
/// number m of fan triangles, and the fan's end points p_1 and p_{m-1} as
/// the last Figure 7 test projected them (valid for a fan of
/// `tested_triangles` triangles; build_fan reuses them).
struct CreepPlan {
  CreepVerdict verdict = CreepVerdict::Build;
  Corner corner{};
  int triangles = 1;
  int tested_triangles = 0;
  Vec3 p1 = Vec3::Zero(), pm = Vec3::Zero();
  Index cell1 = kInvalidIndex, cellm = kInvalidIndex;
};

/// Plans the creep at departure vertex v: the fan of ceil(theta / 60°)
/// triangles over the hole angle theta, or of m ± 1 if that one does not fit
/// the hole wedges of v's front neighbours (Figure 7), else a forced wing, a
/// hold next to a held neighbour, a deferral or "stuck"; then the fold check
/// and the collision net (fan_collision). Carries out what it decides except
/// Build (creep.cpp). Throws TopologyError if the front angle at v is
/// undefined or the mesh folds at v.
CreepPlan plan_creep(FrontState& fs, Vertex v);

/// Figure 6: the fan of plan.triangles triangles at v, its new points at the
/// tangent-disc radius r, projected onto the skin along the normal lines
/// (creep.cpp).
void build_fan(FrontState& fs, Vertex v, const CreepPlan& plan);

/// creep() at departure vertex v: plan_creep, then build_fan if the plan says
/// Build (creep.cpp, Figures 6 and 7).
void creep(FrontState& fs, Vertex v);

/// wing() at front vertex v: the triangle (v, w, u) over a front angle below
/// 90° (forced: below 180°); false if refused (wing.cpp, Figure 7).
bool wing(FrontState& fs, Vertex v, bool force);
/// Why wing(v, force) would refuse, or nullptr if it can be done.
const char* wing_refusal(const FrontState& fs, Vertex v, bool force);
/// Wings every vertex queued by the last operation that wants one.
void drain_wings(FrontState& fs);

/// bridge() at saddle c if the front has reached it from two sides; false if
/// it is not ready (bridge.cpp, Figure 8).
bool try_bridge(FrontState& fs, Index c);
/// The rails of a ladder of `rows` rows from front edge a->b to c->d: the
/// inner points of the left rail a -> d and of the right rail b -> c, pulled
/// back onto the skin (with their mixed cells); empty for one row.
Rails ladder_rails(const FrontState& fs, Halfedge ab, Halfedge cd, int rows);
/// True if the ladder's triangles fit in the hole wedges of a, b, c and d in
/// their own tangent planes (at a they span from b to the first left rail
/// point, at b from the first right rail point to a, and so on). With rows > 1
/// the rail points are pulled back onto the skin and can leave a wedge that
/// the straight quad fits (src kinase at probe 0).
bool ladder_fits(const FrontState& fs, Halfedge ab, Halfedge cd, const Rails& rails);
/// Joins front edges a->b and c->d by a ladder of two triangles per row whose
/// inner rail points are `rails` (ladder_rails; empty for one row); c is the
/// saddle being bridged (its held vertices are released) or kInvalidIndex for
/// a contact.
void bridge(FrontState& fs, Halfedge ab, Halfedge cd, Index c, const Rails& rails);

/// seal(): closes every remaining hole (seal.cpp).
void seal_all(FrontState& fs);
/// Closes the hole of boundary loop h (DP fill, else ear clipping); a hole
/// that is tangled in every projection is first enlarged by deleting the
/// faces around it (at most `enlargements_left` times); with `in_sweep` (a
/// small hole met during the sweep) it is re-opened instead.
void seal_loop(FrontState& fs, Halfedge h, int enlargements_left, bool in_sweep = false);

// ---------------------------------------------------------------------------
// The driver of Algorithm 1 (sweep.cpp)

/// Algorithm 1 from start to end: initial front, departures until the queue
/// is empty (releasing unbridged saddles), seal. The result takes the mesh.
SweepResult run_sweep(FrontState& fs);
/// creation() at every live minimum.
void create_initial_front(FrontState& fs);
/// One iteration of Algorithm 1's loop (lines 2–14): the lowest valid
/// departure vertex is held (a ready saddle is bridged), closes a small hole,
/// or creeps; after a hold or a creep the wings are drained. False if the
/// queue was empty.
bool departure_step(FrontState& fs);
/// The departures until the queue is empty (releasing unbridged saddles),
/// then the seal: run_sweep after its initial front (sweep_region's too).
void sweep_and_seal(FrontState& fs);
/// Removes the sweep's own vertex properties and grids; the mesh keeps
/// those of SweepResult::mesh.
void drop_sweep_properties(FrontState& fs);
/// The progress guarantee, not in the paper: counts a departure of v and
/// returns false while v has departed fewer than max_departures times;
/// otherwise v is left for the seal (leave_hole_for_seal, counted in
/// spent_vertices) and true is returned (papers/front/sweep.md, "Progress").
bool departure_spent(FrontState& fs, Vertex v);
/// Not in the paper: true (and v parked) if departure vertex v has come
/// within about park_factor · r of the upper cut of the region being swept
/// (front/region.h; never for the whole skin). With
/// Region::holds_before_parking, a v that a critical point holds never parks.
bool parks(FrontState& fs, Vertex v);
/// Parks departure vertex v below the region's upper cut: held by no
/// critical point, given the role Parked, so that it never departs and its
/// loop is left open for the band.
void park(FrontState& fs, Vertex v);
/// Releases the vertices held by unresolved saddles (the queue ran dry before
/// both sides arrived); returns true if any was released (holds.cpp).
bool release_saddles(FrontState& fs);

// Vertices and the queue (front_state.cpp), the holds (holds.cpp).
/// A new front vertex at p (on the skin; `cell` a hint for its mixed cell),
/// with its normal, rho and cell. Throws TopologyError when the vertex budget
/// (a runaway guard that follows the smallest rho met) is exceeded.
Vertex new_vertex(FrontState& fs, const Vec3& p, Index cell);
/// Queues v at its height.
void push(FrontState& fs, Vertex v);
/// Re-queues v a little higher (defer_step · r more per deferral) so that the
/// front moves on around it first.
void defer(FrontState& fs, Vertex v, double r);
/// Normal-line projection of v + r dir onto the skin (papers/skin/skin_math.md
/// §7.2); if `cell` is given, the mixed cell of the projected point is written
/// there (the hint for new_vertex(), which then need not walk to it again).
Vec3 project_tangent(FrontState& fs, Vertex v, const Vec3& dir, double r, Index* cell = nullptr);
/// The unresolved live saddle or maximum whose protecting sphere v's tangent
/// disc meets (the nearest), or kInvalidIndex.
Index hold_region(const FrontState& fs, Vertex v);
/// In a region whose upper cut detours (front/region.h): 0 if v lies away from
/// the balls of the detours (the height rule applies), else +1 if v lies
/// within park_factor · r of the cut's polyline (it parks), -1 if not.
int near_upper_detour(const FrontState& fs, Vertex v);
/// Marks v held by critical point c; a saddle is bridged when it is ready.
void hold(FrontState& fs, Vertex v, Index c);
/// Releases every vertex held by c (after its bridge, or unbridged); with
/// `requeue`, the released front vertices are queued again. Returns true if
/// any was queued.
bool release_holds(FrontState& fs, Index c, bool requeue);
/// Reports the swept fraction of the height range to run.progress; throws
/// Cancelled (core/errors.h) once run.cancel is set.
void report_progress(FrontState& fs, double h);

// ---------------------------------------------------------------------------
// Not in the paper: the collision safety net (collision_net.cpp)

/// If a free front vertex x of another part of the front lies within
/// contact_radius · r of v, inside v's hole wedge and with v inside x's, the
/// two front parts are joined by one ladder row (a contact) and true is
/// returned; if x is held, v joins the hold instead.
bool try_contact(FrontState& fs, Vertex v, const Corner& k);
/// Joins v's front to front vertex x by one ladder row, if one of the two
/// quads (v->w with x_u->x, u->v with x->x_w) is convex and fits.
bool contact_with(FrontState& fs, Vertex v, const Corner& k, Vertex x);
/// The fan of m triangles at v (corner k) would bring a new point within
/// collision_radius · r of another vertex x: v is held (x held), joined to x
/// (contact) or deferred, and true is returned; deferred too often, v is left
/// for the seal if x is an interior vertex and the fallback is on (true);
/// false if the fan is clear or is built anyway.
bool fan_collision(FrontState& fs, Vertex v, const Corner& k, int m);
/// The free or held front vertex x (not v, w or u, on v's sheet: normals
/// within acos(min_normal_cosine)) that the triangle (v, w, u) would cover:
/// x lies within max(|w - v|, |u - v|) of v and projects along v's normal
/// strictly inside the triangle's three edges.
/// The nearest to v, ties to the lower index; invalid if there is none. Cost:
/// one front_grid query of radius max(|w - v|, |u - v|) around v.
/// Not in the paper: there, fronts meet only inside protecting spheres, and a
/// triangle over a front angle is empty (papers/front/collision_net.md, "A
/// triangle over another front").
Vertex covered_front_vertex(const FrontState& fs, Vertex v, Vertex w, Vertex u);
/// The mesh folds at departure vertex v (its tangent angles and hole angle do
/// not make 360°, or its front angle is undefined), and the fallback is on:
/// the faces around v are re-opened (reopen_hole; verdict Reopened), or, if
/// that is no longer allowed there, v is left for the seal
/// (leave_hole_for_seal; verdict Stuck). papers/front/patch.md.
CreepVerdict leave_fold(FrontState& fs, Vertex v);

// Not in the paper: hole filling (hole_filling.cpp, seal.cpp)

/// True if the front loop through v bounds a small hole (at most
/// small_hole_vertices vertices within small_hole_reach · r of v).
bool small_hole(const FrontState& fs, Vertex v);
/// Closes the small hole of the front loop through v during the sweep (DP
/// fill, else ear clipping in a plane where it is simple). A small hole
/// tangled in every plane is not enlarged into the rest of the front (that
/// would seal a front the sweep has not finished): the faces around it are
/// deleted and their surviving corners go back on the front (reopen_hole).
void close_small_hole(FrontState& fs, Vertex v);
/// Triangulates the hole bounded by `poly` (its vertices in boundary-loop
/// order) by dynamic programming over all its triangulations, maximising the
/// minimum angle among those whose triangles face outwards at their three
/// corners and create no existing edge; false if there is none.
bool fill_hole_dp(FrontState& fs, const std::vector<Vertex>& poly);
/// Deletes the faces incident to the vertices of `poly` and returns a
/// boundary half-edge of the enlarged hole (invalid if it pinched); the
/// surviving corners of the deleted faces go to `rim` if given.
Halfedge enlarge_hole(FrontState& fs, const std::vector<Vertex>& poly, std::vector<Vertex>* rim = nullptr);
/// Deletes the faces around `poly`, grown until no corner is pinched, and puts
/// the corners that keep a face back on the front and in the queue, so that
/// the sweep re-meshes the region. False (nothing changed) if the region would
/// not stop pinching or a vertex was re-opened too often.
bool reopen_hole(FrontState& fs, const std::vector<Vertex>& poly);
/// Leaves the tangled small hole `poly` (or a departure vertex the fallback
/// stops) open for the seal: its vertices are held by no critical point (as
/// stuck ones are), so that the sweep goes on around it (papers/front/patch.md).
void leave_hole_for_seal(FrontState& fs, const std::vector<Vertex>& poly);

// ---------------------------------------------------------------------------
// Not in the paper: the fallback where the front tangles (patch.cpp)

/// Re-meshes a region around the vertices `around` (a hole that cannot be
/// closed): the faces within a few rings of them are replaced by the
/// restricted Delaunay triangulation of a sample of the skin inside the
/// region (the region's own vertices, thinned, and surface Delaunay centres
/// inserted until every patch facet meets [U]), conforming to the region's
/// boundary loop, embedded among the kept faces around it and outward at
/// every corner; the region grows by rings until such a patch exists.
/// Returns false (mesh unchanged) if none does within the largest region, or
/// if SweepOptions::patch_fallback is off. Counts patched_holes and
/// patch_faces. If none of `around` is left (an enlargement deleted the
/// hole's neighbourhood), the region starts from the front vertices nearest
/// to `near` (Å).
bool patch_hole(FrontState& fs, const std::vector<Vertex>& around, const Vec3& near);

// ---------------------------------------------------------------------------
// The front's geometry in tangent planes (front_geometry.cpp)

/// The corner of the front at boundary vertex v.
Corner corner(const FrontState& fs, Vertex v);
/// True if the hole angle at boundary vertex v is certainly at least `bound`
/// (radians), decided from the sine and cosine alone; false if it may be below
/// (then corner(v).angle decides). Decides only bounds of at most 90° or 180°
/// (give or take 1e-12 rad).
bool clearly_not_below(const FrontState& fs, Vertex v, double bound);
/// True if the quad a b c d (two front edges a->b, c->d joined by a bridge
/// row) is convex and counter-clockwise in the plane through `origin` with
/// normal `normal`, and its triangles fit the hole wedges at its four corners
/// (papers/front/open_questions.md Q6.2 (bridge quads)).
bool quad_fits(const FrontState& fs, Vertex a, Vertex b, Vertex c, Vertex d, const Vec3& origin, const Vec3& normal);
/// True if a new triangle at front vertex x spanning counter-clockwise (in
/// T_x) from the direction of y_from to that of y_to lies inside x's hole
/// wedge, so that it cannot fold over the triangles already at x.
bool fits_at(const FrontState& fs, Vertex x, Vertex y_from, Vertex y_to);
/// The same for a triangle whose other corners are at positions `from`, `to`
/// (y_from / y_to: their vertices, or invalid for points not created yet).
bool fits_at(const FrontState& fs, Vertex x, const Vec3& from, const Vec3& to, Vertex y_from, Vertex y_to);
/// Sum of the tangent-plane angles at v of its triangles, plus the hole angle
/// if v is on the front, minus 360° (radians): ~0 unless the mesh folds.
double fold_excess(const FrontState& fs, Vertex v);
/// With opt.paranoid, checks fold_excess at the vertices of the faces added
/// since `first_face` and throws TopologyError naming the operation.
void paranoid_check(FrontState& fs, std::size_t first_face, const char* op);

}  // namespace skinmesh::front::detail

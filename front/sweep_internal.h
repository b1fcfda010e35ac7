// front/sweep_internal.h: the private header of the sweep — the state shared
// by the operations of Algorithm 1 (Cheng & Shi 2004 §4.1), each defined in its
// own file:
//   sweep.cpp          Algorithm 1: the queue, departures, holds, releases
//   front_geometry.cpp corners, hole wedges and the fold test in tangent planes
//   creation.cpp       creation() at a minimum (Figure 5)
//   creep.cpp          creep() at the departure vertex (Figures 6, 7)
//   wing.cpp           wing() at a front angle below 90° (Figure 7)
//   bridge.cpp         bridge() at a saddle, the ladder (Figure 8)
//   seal.cpp           seal() of the holes at maxima
//   collision_net.cpp  the project's safety net: fan collisions, contacts
//   hole_filling.cpp   the project's hole filling: small holes, the
//                      max-min-angle programme, enlargement of tangled holes
// Only front/*.cpp and the unit tests of tests/front include this header.
// Notes: papers/front/README.md
#pragma once

#include <cmath>
#include <limits>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <numbers>
#include <queue>
#include <string>
#include <vector>

#include "front/sweep.h"
#include "geometry/triangulation/point_grid.h"
#include "geometry/mesh/surface_mesh.h"

namespace skinmesh::front::detail {

using geometry::Face;
using geometry::Halfedge;
using geometry::SurfaceMesh;
using geometry::Vertex;

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kDeg = kPi / 180.0;

/// Angular tolerance (radians) of the hole-wedge tests: spans that agree to
/// this are taken as equal (tangent angles are accurate to ~1e-12 rad).
inline constexpr double kWedgeTolerance = 1e-6;

/// Unit tangent direction from p towards x, in the tangent plane with unit
/// normal n; zero if x - p is parallel to n.
inline Vec3 tangent_dir(const Vec3& p, const Vec3& n, const Vec3& x) {
  Vec3 d = x - p;
  d -= d.dot(n) * n;
  const double len = d.norm();
  return len > 0 ? Vec3(d / len) : Vec3::Zero();
}

/// Counter-clockwise angle (about unit n) from unit tangent a to unit tangent
/// b, in [0, 2 pi).
inline double ccw_angle(const Vec3& a, const Vec3& b, const Vec3& n) {
  double t = std::atan2(a.cross(b).dot(n), a.dot(b));
  if (t < 0) t += 2 * kPi;
  return t;
}

/// A pseudo-angle of the direction (x, y) (a tangent's coordinates along
/// and across a reference direction): a monotone map of the angle
/// t = atan2(y, x) taken in [0, 2 pi) as ccw_angle() takes it (including
/// its treatment of signed zeros) onto [0, 4], with dt/dp between 1 and 2,
/// so that pseudo-angle differences bound angle differences:
/// p1 - p0 <= t1 - t0 <= 2 (p1 - p0) for p1 >= p0. Costs a division, no
/// atan2. (0, 0) gives 0, as atan2(0, 0); a NaN gives NaN.
inline double pseudo_angle(double y, double x) {
  const double s = std::abs(x) + std::abs(y);
  if (s == 0) return 0.0;
  const double c = x / s;
  return y >= 0 ? 1 - c : 3 + c;
}

/// Three-valued test of t1 - t0 > tol from pseudo-angles p1, p0 of t1, t0
/// (pseudo_angle, angles in radians): 1 if it certainly holds, 0 if it
/// certainly fails, -1 if the pseudo-angles cannot tell (within a factor of
/// two of tol, or NaN); 1e-12 covers the rounding of both sides.
inline int pseudo_exceeds(double p1, double p0, double tol) {
  const double d = p1 - p0;
  if (d > tol + 1e-12) return 1;
  if (2 * d < tol - 1e-12) return 0;
  return -1;
}

/// ccw_angle() to within 2e-5 rad for tangent vectors a, b of any nonzero
/// length (zero vectors give 0), for tests with a tolerance of degrees
/// (fold_excess): a polynomial arctangent on [0, 1] (minimax, degree 9,
/// odd; the usual octant reduction) instead of std::atan2, and no
/// normalisation (the angle does not depend on the lengths).
inline double coarse_ccw_angle(const Vec3& a, const Vec3& b, const Vec3& n) {
  const double y = a.cross(b).dot(n), x = a.dot(b);
  const double ax = std::abs(x), ay = std::abs(y);
  const double hi = std::max(ax, ay), lo = std::min(ax, ay);
  if (!(hi > 0)) return 0.0;
  const double z = lo / hi, z2 = z * z;
  double t = z * (0.99986600 + z2 * (-0.33029950 + z2 * (0.18014100 + z2 * (-0.08513300 + z2 * 0.02083510))));
  if (ay > ax) t = kPi / 2 - t;
  if (x < 0) t = kPi - t;
  if (y < 0) t = 2 * kPi - t;
  return t >= 2 * kPi ? t - 2 * kPi : t;
}

/// Rotates tangent vector a about unit axis n by angle t (radians).
inline Vec3 rotate(const Vec3& a, const Vec3& n, double t) {
  return std::cos(t) * a + std::sin(t) * n.cross(a) + (1 - std::cos(t)) * n.dot(a) * n;
}

/// State of a mesh vertex during the sweep.
enum class VState : std::uint8_t {
  Interior,  ///< every triangle around it is there
  Front,     ///< on the front, free to depart
  Held,      ///< on the front, stopped in a protecting sphere (or stuck)
};

/// The sweep: the partial mesh, the departure queue and the holds. The front
/// is the set of boundary half-edges of the partial SurfaceMesh (a boundary
/// half-edge has the hole on its left; faces are counter-clockwise about the
/// outward normal), so there is no second front list to keep in sync
/// (papers/front/open_questions.md Q1.1).
class Sweep {
 public:
  /// Prepares an empty mesh and the grids of the protecting spheres and of the
  /// vertices. Throws std::invalid_argument if opt.disc_factor lies outside
  /// the tangent-disc window of opt.size. `skin`, `ms` and `opt` must outlive
  /// the sweep.
  Sweep(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const SweepOptions& opt);

  /// Algorithm 1 from start to end: initial front, departures until the queue
  /// is empty (releasing unbridged saddles), seal. The result takes the mesh.
  SweepResult run();

  // Algorithm 1, one step at a time (sweep.cpp); run() is made of these.
  /// creation() at every live minimum.
  void create_initial_front();
  /// One iteration of Algorithm 1's loop (lines 2–14): the lowest valid
  /// departure vertex is held (a ready saddle is bridged), closes a small
  /// hole, or creeps; after a hold or a creep the wings are drained. False if
  /// the queue was empty.
  bool departure_step();
  /// Releases the vertices held by unresolved saddles (the queue ran dry
  /// before both sides arrived); returns true if any was released.
  bool release_saddles();

  // Algorithm 1's operations.
  /// creation() at minimum c: a bowl of six triangles (creation.cpp, Figure 5).
  void creation(Index c);
  /// creep() at departure vertex v: a fan of ceil(theta/60°) triangles, after
  /// the Figure 7 test (creep.cpp, Figure 6).
  void creep(Vertex v);
  /// wing() at front vertex v: the triangle (v, w, u) over a front angle below
  /// 90° (forced: below 180°); false if refused (wing.cpp, Figure 7).
  bool wing(Vertex v, bool force);
  /// Why wing(v, force) would refuse, or nullptr if it can be done.
  const char* wing_refusal(Vertex v, bool force) const;
  /// Wings every vertex queued by the last operation that wants one.
  void drain_wings();
  /// bridge() at saddle c if the front has reached it from two sides; false
  /// if it is not ready (bridge.cpp, Figure 8).
  bool try_bridge(Index c);
  /// The rails of a ladder of `rows` rows from front edge a->b to c->d: the
  /// inner points of the left rail a -> d and of the right rail b -> c, pulled
  /// back onto the skin (with their mixed cells); empty for one row.
  struct Rails {
    std::vector<Vec3> left, right;
    std::vector<Index> left_cell, right_cell;
  };
  Rails ladder_rails(Halfedge ab, Halfedge cd, int rows) const;
  /// True if the ladder's triangles fit in the hole wedges of a, b, c and d
  /// in their own tangent planes (at a they span from b to the first left
  /// rail point, at b from the first right rail point to a, and so on). With
  /// rows > 1 the rail points are pulled back onto the skin and can leave a
  /// wedge that the straight quad fits (src kinase at probe 0).
  bool ladder_fits(Halfedge ab, Halfedge cd, const Rails& rails) const;
  /// Joins front edges a->b and c->d by a ladder of two triangles per row
  /// whose inner rail points are `rails` (ladder_rails; empty for one row);
  /// c is the saddle being bridged (its held vertices are released) or
  /// kInvalidIndex for a contact.
  void bridge(Halfedge ab, Halfedge cd, Index c, const Rails& rails);
  /// seal(): closes every remaining hole (seal.cpp).
  void seal_all();
  /// Closes the hole of boundary loop h (DP fill, else ear clipping); a hole
  /// that is tangled in every projection is first enlarged by deleting the
  /// faces around it (at most `enlargements_left` times); with `in_sweep`
  /// (a small hole met during the sweep) it is re-opened instead.
  void seal_loop(Halfedge h, int enlargements_left, bool in_sweep = false);
  /// Closes the small hole of the front loop through v during the sweep (DP
  /// fill, else ear clipping in a plane where it is simple). A small hole
  /// tangled in every plane is not enlarged into the rest of the front (that
  /// would seal a front the sweep has not finished): the faces around it are
  /// deleted and their surviving corners go back on the front (reopen_hole).
  void close_small_hole(Vertex v);
  /// Deletes the faces around `poly`, grown until no corner is pinched, and
  /// puts the corners that keep a face back on the front and in the queue, so
  /// that the sweep re-meshes the region. False (nothing changed) if the
  /// region would not stop pinching or a vertex was re-opened too often.
  bool reopen_hole(const std::vector<Vertex>& poly);

  // The collision safety net (collision_net.cpp), not in the paper.
  /// Front geometry at a boundary vertex v: u -> v -> w with the hole on the left.
  struct Corner {
    Vertex u, w;
    Halfedge in, out;
    double angle;  ///< hole angle at v (radians), measured in T_v
    Vec3 dw;       ///< unit tangent direction to w
  };
  /// If a free front vertex x of another part of the front lies within
  /// contact_radius · r of v, inside v's hole wedge and with v inside x's,
  /// the two front parts are joined by one ladder row (a contact) and true
  /// is returned; if x is held, v joins the hold instead.
  bool try_contact(Vertex v, const Corner& k);
  /// Joins v's front to front vertex x by one ladder row, if one of the two
  /// quads (v->w with x_u->x, u->v with x->x_w) is convex and fits.
  bool contact_with(Vertex v, const Corner& k, Vertex x);
  /// The fan of m triangles at v (corner k) would bring a new point within
  /// collision_radius · r of another vertex x: v is held (x held), joined to
  /// x (contact) or deferred, and true is returned; false if the fan is clear
  /// or v has been deferred too often (the fan is built anyway).
  bool fan_collision(Vertex v, const Corner& k, int m);

  // Hole filling (hole_filling.cpp), not in the paper.
  /// True if the front loop through v bounds a small hole (at most
  /// small_hole_vertices vertices within small_hole_reach · r of v).
  bool small_hole(Vertex v) const;
  /// Triangulates the hole bounded by `poly` (its vertices in boundary-loop
  /// order) by dynamic programming over all its triangulations, maximising the
  /// minimum angle among those whose triangles face outwards at their three
  /// corners and create no existing edge; false if there is none.
  bool fill_hole_dp(const std::vector<Vertex>& poly);
  /// Deletes the faces incident to the vertices of `poly` and returns a
  /// boundary half-edge of the enlarged hole (invalid if it pinched).
  Halfedge enlarge_hole(const std::vector<Vertex>& poly);

  // Front geometry in tangent planes (front_geometry.cpp).
  /// The corner of the front at boundary vertex v.
  Corner corner(Vertex v) const;
  /// True if the hole angle at boundary vertex v is certainly at least
  /// `bound` (radians), decided from the sine and cosine alone; false if it
  /// may be below (then corner(v).angle decides). Decides only bounds of at
  /// most 90° or 180° (give or take 1e-12 rad).
  bool clearly_not_below(Vertex v, double bound) const;
  /// True if the quad a b c d (two front edges a->b, c->d joined by a bridge
  /// row) is convex and counter-clockwise in the plane through `origin` with
  /// normal `normal`, and its triangles fit the hole wedges at its four
  /// corners (papers/front/open_questions.md Q6.2).
  bool quad_fits(Vertex a, Vertex b, Vertex c, Vertex d, const Vec3& origin, const Vec3& normal) const;
  /// True if a new triangle at front vertex x spanning counter-clockwise (in
  /// T_x) from the direction of y_from to that of y_to lies inside x's hole
  /// wedge, so that it cannot fold over the triangles already at x.
  bool fits_at(Vertex x, Vertex y_from, Vertex y_to) const;
  /// The same for a triangle whose other corners are at positions `from`,
  /// `to` (y_from / y_to: their vertices, or invalid for points not created yet).
  bool fits_at(Vertex x, const Vec3& from, const Vec3& to, Vertex y_from, Vertex y_to) const;
  /// Sum of the tangent-plane angles at v of its triangles, plus the hole
  /// angle if v is on the front, minus 360° (radians): ~0 unless the mesh folds.
  double fold_excess(Vertex v) const;
  /// With opt.paranoid, checks fold_excess at the vertices of the faces added
  /// since `first_face` and throws TopologyError naming the operation.
  void paranoid_check(std::size_t first_face, const char* op);
  /// Tells opt.observer (if any) that `op` ran at departure vertex v (or
  /// invalid) for critical point c (or kInvalidIndex), adding the faces from
  /// first_face on.
  void notify(SweepOperation op, Vertex v, Index c, std::size_t first_face) const {
    if (opt_.observer) opt_.observer(SweepEvent{op, v, c, first_face, mesh_, stats_});
  }

  // Read access for the unit tests.
  const SurfaceMesh& mesh() const { return mesh_; }
  const SweepStats& stats() const { return stats_; }
  VState state(Vertex v) const { return state_[v]; }
  const Vec3& normal(Vertex v) const { return normal_[v]; }
  /// The tangent-disc radius r = disc_factor · rho at v (Å), Figure 6.
  double disc_radius(Vertex v) const { return opt_.disc_factor * rho_[v]; }

 private:
  // Vertices, the queue and the holds (sweep.cpp).
  Vertex new_vertex(const Vec3& p, Index cell);
  /// Sets v's state, and keeps front_grid_ to the vertices not Interior.
  void set_state(Vertex v, VState s) {
    if ((s == VState::Interior) != (state_[v] == VState::Interior)) {
      if (s == VState::Interior)
        front_grid_->erase(v.idx());
      else
        front_grid_->insert(v.idx(), mesh_.position(v));
    }
    state_[v] = s;
  }
  void push(Vertex v);
  /// Re-queues v a little higher (defer_step · r more per deferral) so that
  /// the front moves on around it first.
  void defer(Vertex v, double r);
  double height(Vertex v) const { return e_.dot(mesh_.position(v)); }
  /// Normal-line projection of v + r dir onto the skin (papers/skin/skin_math.md §7.2);
  /// if `cell` is given, the mixed cell of the projected point is written there
  /// (the hint for new_vertex(), which then need not walk to it again).
  Vec3 project_tangent(Vertex v, const Vec3& dir, double r, Index* cell = nullptr);
  /// The unresolved live saddle or maximum whose protecting sphere v's tangent
  /// disc meets (the nearest), or kInvalidIndex.
  Index hold_region(Vertex v) const;
  /// The critical point holding x, or kInvalidIndex (x free, interior, or
  /// stuck: held by no critical point).
  Index holder_of(Vertex x) const { return state_[x] == VState::Held ? held_by_[x] : kInvalidIndex; }
  /// Marks v held by critical point c; a saddle is bridged when it is ready.
  void hold(Vertex v, Index c);
  /// Releases every vertex held by c (after its bridge, or unbridged); with
  /// `requeue`, the released front vertices are queued again. Returns true if
  /// any was queued.
  bool release_holds(Index c, bool requeue);
  Face add_triangle(Vertex a, Vertex b, Vertex c) { return mesh_.add_triangle(a, b, c); }
  /// Reports the swept fraction of the height range to opt.progress.
  void report_progress(double h);

  /// printf-style line to opt_.trace.
  template <class... Args>
  void tracef(const char* fmt, Args... args) const {
    char buf[512];
    std::snprintf(buf, sizeof buf, fmt, args...);
    std::string line(buf);
    if (!line.empty() && line.back() == '\n') line.pop_back();
    opt_.trace(line);
  }

  struct QueueEntry {
    double h;
    Index v;
    std::uint32_t stamp;
    bool operator>(const QueueEntry& o) const { return h != o.h ? h > o.h : v > o.v; }
  };

  const skin::SkinSurface& skin_;
  const morse::MorseSmaleComplex& ms_;
  const SweepOptions& opt_;
  const Vec3 e_;
  SurfaceMesh mesh_;
  geometry::VertexProperty<Vec3> normal_;
  geometry::VertexProperty<double> rho_;
  geometry::VertexProperty<Index> cell_;
  geometry::VertexProperty<VState> state_;
  geometry::VertexProperty<Index> held_by_;
  geometry::VertexProperty<std::uint32_t> stamp_;
  geometry::VertexProperty<std::uint8_t> deferrals_;
  geometry::VertexProperty<std::uint8_t> reopenings_;  ///< re-opened regions whose rim held the vertex
  /// Departure queue: a min-heap on height with lazy deletion by stamp
  /// (papers/front/open_questions.md Q1.2).
  std::priority_queue<QueueEntry, std::vector<QueueEntry>, std::greater<>> queue_;
  std::vector<Vertex> wing_worklist_;
  /// Scratch lists of creep() (the fan) and try_contact() (the vertices a
  /// few hops along the front), kept to reuse their memory; neither call
  /// re-enters itself.
  std::vector<Vertex> scratch_fan_, scratch_near_hops_;
  std::vector<char> resolved_;              ///< saddle bridged or released (holds no more)
  std::vector<std::vector<Vertex>> held_;   ///< vertices held per critical point
  std::unique_ptr<geometry::PointGrid> hold_grid_;
  std::unique_ptr<geometry::ErasablePointGrid> vertex_grid_;  ///< every vertex, for the collision safety net
  /// The vertices whose state is not Interior (the front, free or held): the
  /// contact search reads only these (set_state keeps it).
  std::unique_ptr<geometry::ErasablePointGrid> front_grid_;
  double max_hold_radius_ = 0;
  long steps_ = 0;                  ///< departures so far (for max_steps)
  double h_min_ = 0, h_max_ = 0;    ///< height range of the critical points (progress)
  double next_progress_ = 0;        ///< next fraction to report
  const bool trace_ = static_cast<bool>(opt_.trace);
  std::size_t vertex_budget_ = 0;     ///< runaway guard (new_vertex)
  double base_vertex_budget_ = 0;     ///< the budget at the atoms' scale
  double rho_max_ = 0;                ///< largest sphere radius sqrt(w/2) (Å)
  double rho_min_seen_ = std::numeric_limits<double>::infinity();  ///< smallest rho of a vertex so far (Å)
  SweepStats stats_;
};

}  // namespace skinmesh::front::detail

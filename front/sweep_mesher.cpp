// front/sweep_mesher.cpp: the sweep of Cheng & Shi 2004 §4.1 (Algorithm 1).
//
// The front is the set of boundary half-edges of the partial SurfaceMesh (a
// boundary half-edge has the hole on its left; faces are counter-clockwise
// about the outward normal), so there is no second front list to keep in sync
// (sweep-design-notes Q1.1). Departure vertices come from a min-heap keyed by
// height with lazy deletion (Q1.2).
#include "front/sweep_mesher.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <numbers>
#include <queue>

#include <Eigen/Eigenvalues>
#include <sstream>

#include "geometry/assert.h"
#include "geometry/errors.h"
#include "geometry/mesh_checks.h"
#include "geometry/mesh_io.h"
#include "geometry/point_grid.h"
#include "geometry/predicates.h"
#include "refine/local_refinement.h"

namespace skinmesh::front {

using geometry::Face;
using geometry::Halfedge;
using geometry::SurfaceMesh;
using geometry::Vertex;
using geometry::min_angle;
using morse::CriticalKind;

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

/// State of a mesh vertex during the sweep.
enum class VState : std::uint8_t { Interior, Front, Held };

/// Unit tangent direction from p towards x, in the tangent plane with normal n.
Vec3 tangent_dir(const Vec3& p, const Vec3& n, const Vec3& x) {
  Vec3 d = x - p;
  d -= d.dot(n) * n;
  const double len = d.norm();
  return len > 0 ? Vec3(d / len) : Vec3::Zero();
}

/// Counter-clockwise angle (about n) from unit tangent a to unit tangent b, in [0, 2 pi).
double ccw_angle(const Vec3& a, const Vec3& b, const Vec3& n) {
  double t = std::atan2(a.cross(b).dot(n), a.dot(b));
  if (t < 0) t += 2 * kPi;
  return t;
}

/// Rotates tangent vector a about unit axis n by angle t.
Vec3 rotate(const Vec3& a, const Vec3& n, double t) {
  return std::cos(t) * a + std::sin(t) * n.cross(a) + (1 - std::cos(t)) * n.dot(a) * n;
}

// Sweep Definition

class Sweep {
 public:
  Sweep(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const SweepOptions& opt)
      : skin_(skin), ms_(ms), opt_(opt), e_(ms.height_direction) {
    normal_ = mesh_.add_vertex_property<Vec3>("v:normal", Vec3::Zero());
    rho_ = mesh_.add_vertex_property<double>("v:rho", 0.0);
    cell_ = mesh_.add_vertex_property<Index>("v:cell", kInvalidIndex);
    state_ = mesh_.add_vertex_property<VState>("v:state", VState::Interior);
    held_by_ = mesh_.add_vertex_property<Index>("v:held_by", kInvalidIndex);
    stamp_ = mesh_.add_vertex_property<std::uint32_t>("v:stamp", 0);
    deferrals_ = mesh_.add_vertex_property<std::uint8_t>("v:deferrals", 0);
    const std::size_t nc = ms.critical.size();
    resolved_.assign(nc, 0);
    held_.resize(nc);
    double rmax = 0;
    for (std::size_t i = 0; i < nc; ++i) rmax = std::max(rmax, ms.protect_radius[i]);
    hold_grid_ = std::make_unique<geometry::PointGrid>(std::max(2 * rmax, 1e-6));
    for (std::size_t i = 0; i < nc; ++i)
      if (ms.live[i] && ms.critical[i].kind != CriticalKind::Minimum)
        hold_grid_->insert(static_cast<Index>(i), ms.critical[i].position);
    max_hold_radius_ = rmax;
    double rho_max = 0;
    for (const auto& wp : skin.points()) rho_max = std::max(rho_max, std::sqrt(std::max(wp.w, 0.0) / 2));
    vertex_grid_ = std::make_unique<geometry::PointGrid>(std::max(opt.disc_factor * rho_max, 1e-6));
    // A generous bound on the vertex count: 8 times what a separate sphere per
    // atom would need (4 pi / (c_r² sqrt(3)/2) vertices per sphere).
    const double per_atom = 4 * kPi / (opt.disc_factor * opt.disc_factor * 0.866);
    vertex_budget_ = static_cast<std::size_t>(1e5 + 8 * per_atom * skin.points().size());
  }

  SweepResult run();

 private:
  // Vertices and the queue
  Vertex new_vertex(const Vec3& p, Index cell);
  void push(Vertex v);
  double height(Vertex v) const { return e_.dot(mesh_.position(v)); }
  double disc_radius(Vertex v) const { return opt_.disc_factor * rho_[v]; }
  Vec3 project_tangent(Vertex v, const Vec3& dir, double r);
  Index hold_region(Vertex v) const;
  /// The critical point holding x, or kInvalidIndex (x free, interior, or
  /// stuck: held by no critical point).
  Index holder_of(Vertex x) const { return state_[x] == VState::Held ? held_by_[x] : kInvalidIndex; }
  /// Marks v held by critical point c; a saddle is bridged when it is ready.
  void hold(Vertex v, Index c);

  // Algorithm 1's operations
  void creation(Index c);
  void creep(Vertex v);
  bool wing(Vertex v, bool force);
  /// Why wing(v, force) would refuse, or nullptr if it can be done.
  const char* wing_refusal(Vertex v, bool force) const;
  void drain_wings();
  bool try_bridge(Index c);
  /// Joins front edges a->b and c->d by a ladder of `rows` rows of two
  /// triangles; c is the saddle being bridged (its held vertices are
  /// released) or kInvalidIndex for a contact.
  void bridge(Halfedge ab, Halfedge cd, Index c, int rows);
  /// Releases the vertices held by unresolved saddles (the queue ran dry before
  /// both sides arrived); returns true if any was released.
  bool release_saddles();
  void seal_all();
  bool small_hole(Vertex v) const;
  /// Closes the hole of boundary loop h (DP fill, else ear clipping); a hole
  /// that is tangled in every projection is first enlarged by deleting the
  /// faces around it (at most `depth_left` times).
  void seal_loop(Halfedge h, int depth_left = 2);
  /// Deletes the faces incident to the vertices of `poly` and returns a
  /// boundary half-edge of the enlarged hole (invalid if it pinched).
  Halfedge enlarge_hole(const std::vector<Vertex>& poly);
  /// Triangulates the hole bounded by `poly` (its vertices in boundary-loop
  /// order) by dynamic programming over all its triangulations, maximising the
  /// minimum angle among those whose triangles face outwards at their three
  /// corners and create no existing edge; false if there is none.
  bool fill_hole_dp(const std::vector<Vertex>& poly);
  Face add_triangle(Vertex a, Vertex b, Vertex c);

  // Front geometry at a boundary vertex v: u -> v -> w with the hole on the left.
  struct Corner {
    Vertex u, w;
    Halfedge in, out;
    double angle;  ///< hole angle at v (radians), measured in T_v
    Vec3 dw;       ///< unit tangent direction to w
  };
  Corner corner(Vertex v) const;
  /// The collision safety net (sweep-design-notes Q2.3): if a free front
  /// vertex x of another part of the front lies within 1.5 r of v, inside v's
  /// hole wedge and with v inside x's, the two front parts are joined by one
  /// ladder row (a contact) and true is returned; if x is held, v joins the
  /// hold instead.
  bool try_contact(Vertex v, const Corner& k);
  /// Joins v's front to front vertex x by one ladder row, if one of the two
  /// quads (v->w with x_u->x, u->v with x->x_w) is convex and fits.
  bool contact_with(Vertex v, const Corner& k, Vertex x);
  /// True if the quad a b c d (two front edges a->b, c->d joined by a
  /// bridge row) is convex and counter-clockwise in the plane through
  /// `origin` with normal `normal`, and its triangles fit the hole wedges at
  /// its four corners (sweep-design-notes Q6.2).
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
  /// Under SKINMESH_PARANOID (environment), checks fold_excess at the vertices
  /// of the faces added since `first_face` and throws naming the operation.
  void paranoid_check(std::size_t first_face, const char* op);

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
  static constexpr std::uint8_t kMaxDeferrals = 8;
  /// Re-queues v a little higher (0.25 r more per deferral) so that the front
  /// moves on around it first.
  void defer(Vertex v, double r) {
    ++deferrals_[v];
    ++stamp_[v];
    queue_.push({height(v) + 0.25 * r * deferrals_[v], v.idx(), stamp_[v]});
    ++stats_.deferred;
  }

  struct QueueEntry {
    double h;
    Index v;
    std::uint32_t stamp;
    bool operator>(const QueueEntry& o) const { return h != o.h ? h > o.h : v > o.v; }
  };
  std::priority_queue<QueueEntry, std::vector<QueueEntry>, std::greater<>> queue_;
  std::vector<Vertex> wing_worklist_;
  std::vector<char> resolved_;              ///< saddle bridged / maximum sealed
  std::vector<std::vector<Vertex>> held_;   ///< vertices held per critical point
  std::unique_ptr<geometry::PointGrid> hold_grid_;
  std::unique_ptr<geometry::PointGrid> vertex_grid_;  ///< every vertex, for the collision safety net
  double max_hold_radius_ = 0;
  long step_ = 0;
  const bool trace_ = static_cast<bool>(opt_.trace);
  /// printf-style line to opt_.trace.
  template <class... Args>
  void tracef(const char* fmt, Args... args) const {
    char buf[512];
    std::snprintf(buf, sizeof buf, fmt, args...);
    std::string line(buf);
    if (!line.empty() && line.back() == '\n') line.pop_back();
    opt_.trace(line);
  }
  std::size_t vertex_budget_ = 0;
  SweepStats stats_;
};

// Vertices, Queue, Projection

Vertex Sweep::new_vertex(const Vec3& p, Index cell) {
  if (mesh_.vertices_size() >= vertex_budget_) {
    std::ostringstream os;
    os << "the front created more than " << vertex_budget_
       << " vertices without closing: it is running away (a bug; please report the input)";
    throw TopologyError(os.str());
  }
  const skin::SkinSample s = skin_.sample(p, cell);
  const Vertex v = mesh_.add_vertex(p);
  vertex_grid_->insert(v.idx(), p);
  normal_[v] = s.gradient.normalized();
  rho_[v] = s.rho;
  cell_[v] = s.cell;
  state_[v] = VState::Front;
  return v;
}

void Sweep::push(Vertex v) {
  ++stamp_[v];
  queue_.push({height(v), v.idx(), stamp_[v]});
}

Vec3 Sweep::project_tangent(Vertex v, const Vec3& dir, double r) {
  // Normal-line projection of q = v + r dir (skin-math §7.2): the bracket
  // [-delta, delta] comes from the sandwiching balls of radius rho(v).
  const double rho = rho_[v];
  const Vec3 n = normal_[v];
  const Vec3 q = mesh_.position(v) + r * dir;
  double delta = rho - std::sqrt(std::max(rho * rho - r * r, 0.0));
  Vec3 out;
  Index cell = cell_[v];
  for (int attempt = 0; attempt < 4; ++attempt, delta *= 2) {
    if (skin_.project_along_line(q, n, delta * (1 + 1e-9) + 1e-12 * skin_.length_scale(), out, cell)) return out;
  }
  // Fall back on the gradient pull-back (skin-math §7.3).
  cell = cell_[v];
  return skin_.pull_back(q, cell);
}

Index Sweep::hold_region(Vertex v) const {
  // v is held if its tangent disc meets the protecting sphere of a live
  // saddle or maximum not yet resolved, so that no fan enters the sphere
  // (Cheng & Shi §4.2: "each step of the front advancing must not cross to the
  // other side of the spheres"); the nearest such critical point holds it.
  const Vec3& p = mesh_.position(v);
  const double r = disc_radius(v);
  Index best = kInvalidIndex;
  double best_d = std::numeric_limits<double>::infinity();
  hold_grid_->for_each_near(p, max_hold_radius_ + r, [&](Index c, const Vec3& q) {
    if (resolved_[c]) return;
    const double d = (p - q).norm();
    if (d < ms_.protect_radius[c] + r && d < best_d) best = c, best_d = d;
  });
  return best;
}

Face Sweep::add_triangle(Vertex a, Vertex b, Vertex c) { return mesh_.add_triangle(a, b, c); }

Sweep::Corner Sweep::corner(Vertex v) const {
  Corner k;
  k.out = mesh_.halfedge(v);
  SKINMESH_ASSERT(mesh_.is_boundary(k.out));
  k.in = mesh_.prev(k.out);
  k.w = mesh_.to_vertex(k.out);
  k.u = mesh_.from_vertex(k.in);
  const Vec3& p = mesh_.position(v);
  const Vec3& n = normal_[v];
  k.dw = tangent_dir(p, n, mesh_.position(k.w));
  const Vec3 du = tangent_dir(p, n, mesh_.position(k.u));
  k.angle = ccw_angle(k.dw, du, n);
  return k;
}

bool Sweep::fits_at(Vertex x, Vertex y_from, Vertex y_to) const {
  return fits_at(x, mesh_.position(y_from), mesh_.position(y_to), y_from, y_to);
}

bool Sweep::fits_at(Vertex x, const Vec3& from, const Vec3& to, Vertex y_from, Vertex y_to) const {
  if (!mesh_.is_boundary(x) || mesh_.is_isolated(x)) return mesh_.is_isolated(x);
  const Corner k = corner(x);
  const Vec3 px = mesh_.position(x), n = normal_[x];
  const double tol = 1e-6;
  const double a = y_from == k.w ? 0.0 : ccw_angle(k.dw, tangent_dir(px, n, from), n);
  const double b = y_to == k.u ? k.angle : ccw_angle(k.dw, tangent_dir(px, n, to), n);
  if (trace_)
    tracef( "fits_at v%u: a %.1f b %.1f hole %.1f (from v%u to v%u; w v%u u v%u)\n", x.idx(), a / kDeg,
                 b / kDeg, k.angle / kDeg, y_from.idx(), y_to.idx(), k.w.idx(), k.u.idx());
  return a < b - tol && b <= k.angle + tol && k.angle > tol;
}

double Sweep::fold_excess(Vertex v) const {
  const Vec3 pv = mesh_.position(v);
  const Vec3 n = normal_[v];
  double covered = 0;
  for (Face f : mesh_.faces(v)) {
    Vertex a, b;
    for (Halfedge h : mesh_.halfedges(f))
      if (mesh_.from_vertex(h) == v) a = mesh_.to_vertex(h), b = mesh_.to_vertex(mesh_.next(h));
    covered += ccw_angle(tangent_dir(pv, n, mesh_.position(a)), tangent_dir(pv, n, mesh_.position(b)), n);
  }
  if (mesh_.is_boundary(v)) covered += corner(v).angle;
  return covered - 2 * kPi;
}

void Sweep::paranoid_check(std::size_t first_face, const char* op) {
  if (!opt_.paranoid) return;
  for (std::size_t fi = first_face; fi < mesh_.faces_size(); ++fi) {
    const Face f(static_cast<Index>(fi));
    if (mesh_.is_deleted(f)) continue;
    for (Vertex v : mesh_.vertices(f)) {
      const double ex = fold_excess(v);
      if (std::abs(ex) > 5 * kDeg) {
        std::ostringstream os;
        os << "paranoid: after " << op << " (faces " << first_face << ".." << mesh_.faces_size()
           << ") the mesh folds at vertex " << v.idx() << " (" << mesh_.position(v).transpose()
           << "): excess " << ex / kDeg << "°";
        if (!opt_.dump_path.empty()) geometry::write_mesh(opt_.dump_path, mesh_.to_indexed_mesh());
        throw TopologyError(os.str());
      }
    }
  }
}

// creation() at a minimum (Cheng & Shi §4.1 "Initial front", Figure 5)

void Sweep::creation(Index c) {
  const morse::CriticalPoint& cp = ms_.critical[c];
  const Vertex p0 = new_vertex(cp.position, cp.cell);
  const Vec3 n = normal_[p0];
  Vec3 t1 = n.unitOrthogonal();
  const double r = disc_radius(p0);
  std::array<Vertex, 6> ring;
  for (int i = 0; i < 6; ++i) {
    const Vec3 dir = rotate(t1, n, i * 60.0 * kDeg);
    const Vec3 p = project_tangent(p0, dir, r);
    ring[i] = new_vertex(p, cell_[p0]);
  }
  for (int i = 0; i < 6; ++i) add_triangle(p0, ring[i], ring[(i + 1) % 6]);
  state_[p0] = VState::Interior;
  for (Vertex v : ring) push(v);
  ++stats_.creations;
}

// creep() at the departure vertex (§4.1 "Creeping triangles", Figure 6)

void Sweep::creep(Vertex v) {
  const double r = disc_radius(v);
  // Copies: new vertices grow the property arrays and would invalidate references.
  const Vec3 n = normal_[v];
  const Vec3 pv = mesh_.position(v);
  Corner k;
  int m = 1;
  // Figure 7: if the first (last) fan triangle would not fit in the hole
  // wedge of w (u), measured in T_w (T_u), or its new point would come close
  // to w's (u's) other neighbour, wing w (u) first and look again.
  for (int attempt = 0;; ++attempt) {
    k = corner(v);
    if (!std::isfinite(k.angle)) {
      std::ostringstream os;
      os << "creep: undefined front angle at vertex " << v.idx() << " (" << pv.transpose()
         << "): a front neighbour coincides with it in the tangent plane";
      throw TopologyError(os.str());
    }
    if (k.angle < 90.0 * kDeg && wing(v, false)) return;
    if (attempt == 0 && try_contact(v, k)) return;
    m = std::max(1, static_cast<int>(std::ceil(k.angle / (60.0 * kDeg) - 1e-9)));
    if (attempt >= 8) break;
    const Vertex w2 = mesh_.to_vertex(mesh_.next(k.out));
    const Vertex u2 = mesh_.from_vertex(mesh_.prev(k.in));
    const Vec3 pw2 = mesh_.position(w2), pu2 = mesh_.position(u2);
    // Figure 7 test of a fan of mm triangles at both ends. For mm = 1 the
    // "fan" is the single triangle (v, w, u). Triangle (v, w, p1) spans from
    // p1 to v at w; (v, p_{m-1}, u) from v to p_{m-1} at u.
    auto test_fan = [&](int mm, bool& bw, bool& bu) {
      const Vec3 p1 = mm == 1 ? mesh_.position(k.u) : Vec3(pv + r * rotate(k.dw, n, k.angle / mm));
      const Vec3 pm = mm == 1 ? mesh_.position(k.w) : Vec3(pv + r * rotate(k.dw, n, k.angle * (mm - 1) / mm));
      const Vertex p1v = mm == 1 ? k.u : Vertex(), pmv = mm == 1 ? k.w : Vertex();
      bw = w2 != k.u && ((mm > 1 && (p1 - pw2).norm() < 0.5 * r) || !fits_at(k.w, p1, pv, p1v, v));
      bu = u2 != k.w && ((mm > 1 && (pm - pu2).norm() < 0.5 * r) || !fits_at(k.u, pv, pm, v, pmv));
    };
    bool bad_w = false, bad_u = false;
    test_fan(m, bad_w, bad_u);
    if (trace_)
      tracef( "creep v%u theta %.1f m %d w v%u u v%u w2 v%u u2 v%u bad_w %d bad_u %d state_u %d\n", v.idx(),
                   k.angle / kDeg, m, k.w.idx(), k.u.idx(), w2.idx(), u2.idx(), bad_w, bad_u, int(state_[k.u]));
    if (bad_w && wing(k.w, true)) continue;
    if (bad_u && wing(k.u, true)) continue;
    // The neighbour's own neighbour may close a narrow spike first.
    if (bad_w && w2 != k.u && wing(w2, true)) continue;
    if (bad_u && u2 != k.w && wing(u2, true)) continue;
    // A fan that would fold over a held neighbour: v joins the hold (it is at
    // the rim of the hold region; the bridge or seal will take care of it).
    const Index holder = bad_w && holder_of(k.w) != kInvalidIndex ? holder_of(k.w)
                         : bad_u                                  ? holder_of(k.u)
                                                                  : kInvalidIndex;
    if (holder != kInvalidIndex) {
      hold(v, holder);
      return;
    }
    if ((bad_w || bad_u) && deferrals_[v] >= kMaxDeferrals) {
      // Last resort before giving up: a fan with more or fewer triangles
      // whose end triangles fit.
      for (int mm : {m + 1, m + 2, m - 1}) {
        if (mm < 1 || (mm == 1 && k.angle >= kPi)) continue;
        bool bw = false, bu = false;
        test_fan(mm, bw, bu);
        if (!bw && !bu) {
          m = mm, bad_w = bad_u = false;
          break;
        }
      }
      if (!bad_w && !bad_u) break;
    }
    if ((bad_w || bad_u) && deferrals_[v] < kMaxDeferrals) {
      // The fan would fold over a neighbour that cannot be winged now: let
      // the front move on around v and try again a little later.
      defer(v, r);
      return;
    }
    if (bad_w || bad_u) {
      // Stuck: no fan fits here even after the front moved on. v stays on the
      // front without departing again; the hole around it is filled when the
      // fronts meet (small hole) or at the seal, and the final checks decide.
      if (trace_)
        tracef("creep: v%u is stuck: its fan would fold over v%u (Figure 7)\n", v.idx(),
                     (bad_w ? k.w : k.u).idx());
      state_[v] = VState::Held;
      held_by_[v] = kInvalidIndex;
      ++stats_.stuck;
      return;
    }
    break;
  }
  // Fold check (sweep-design-notes Q4.1): the tangent angles of the triangles
  // at v plus the hole angle make a full turn.
  if (const double excess = fold_excess(v); std::abs(excess) > 5 * kDeg) {
    std::ostringstream os;
    os << "creep: the mesh folds at vertex " << v.idx() << " (" << pv.transpose() << "): triangles and hole cover "
       << (2 * kPi + excess) / kDeg << "°";
    throw TopologyError(os.str());
  }
  // The safety net for the fan (sweep-design-notes Q4.3 b): a new point
  // within r/2 of a front vertex x other than u, v, w would come too close to
  // another part of the front. Join v to x instead, hold v if x is held, or
  // let the front move on and come back.
  {
    Vertex hit;
    for (int i = 1; i < m && !hit.is_valid(); ++i) {
      const Vec3 q = pv + r * rotate(k.dw, n, i * k.angle / m);
      vertex_grid_->for_each_near(q, 0.5 * r, [&](Index xi, const Vec3&) {
        const Vertex x(xi);
        if (hit.is_valid() || x == v || x == k.u || x == k.w || mesh_.is_deleted(x)) return;
        if (mesh_.is_isolated(x) || normal_[x].dot(n) <= 0.5) return;
        hit = x;  // a front vertex, or an interior one: the fan would cover meshed surface
      });
    }
    if (hit.is_valid()) {
      ++stats_.collisions;
      if (trace_) tracef("collision: fan of v%u reaches v%u\n", v.idx(), hit.idx());
      if (holder_of(hit) != kInvalidIndex) {
        hold(v, holder_of(hit));
        return;
      }
      if (mesh_.is_boundary(hit) && contact_with(v, k, hit)) return;
      if (deferrals_[v] < kMaxDeferrals) {
        defer(v, r);
        return;
      }
    }
  }
  std::vector<Vertex> fan;
  fan.push_back(k.w);
  for (int i = 1; i < m; ++i) {
    const Vec3 dir = rotate(k.dw, n, i * k.angle / m);
    fan.push_back(new_vertex(project_tangent(v, dir, r), cell_[v]));
  }
  fan.push_back(k.u);
  for (int i = 1; i <= m; ++i) add_triangle(v, fan[i - 1], fan[i]);
  state_[v] = VState::Interior;
  for (int i = 1; i < m; ++i) push(fan[i]);
  wing_worklist_.push_back(k.u);
  wing_worklist_.push_back(k.w);
  for (int i = 1; i < m; ++i) wing_worklist_.push_back(fan[i]);
  ++stats_.creeps;
}

// wing(): close a front angle below 90° (§4.1, Figure 7)

bool Sweep::wing(Vertex v, bool force) {
  const char* why = wing_refusal(v, force);
  if (force && why && trace_) tracef("wing v%u refused: %s\n", v.idx(), why);
  if (why) return false;
  const Corner k = corner(v);
  add_triangle(v, k.w, k.u);
  state_[v] = VState::Interior;
  wing_worklist_.push_back(k.u);
  wing_worklist_.push_back(k.w);
  ++stats_.wings;
  return true;
}

const char* Sweep::wing_refusal(Vertex v, bool force) const {
  if (state_[v] != VState::Front || !mesh_.is_boundary(v)) return "not a free front vertex";
  const Corner k = corner(v);
  if (k.angle >= (force ? 180.0 : 90.0) * kDeg) return "front angle too large";
  // A 3-gon is closed only by seal; the new edge u-w must not exist yet.
  if (mesh_.next(k.out) == k.in) return "the front loop is a triangle";
  if (mesh_.find_halfedge(k.w, k.u).is_valid()) return "the edge u-w exists";
  // An unforced wing leaves held neighbours alone (their front edges are what
  // the bridge joins); a forced one (Figure 7) may touch them.
  if (!force && (state_[k.u] == VState::Held || state_[k.w] == VState::Held)) return "a neighbour is held";
  const Vec3 nt = (mesh_.position(k.w) - mesh_.position(v)).cross(mesh_.position(k.u) - mesh_.position(v));
  if (nt.dot(normal_[v]) <= 0) return "the triangle would face inwards";
  // Triangle (v, w, u): at w it spans from u to v, at u from v to w.
  if (!fits_at(k.w, k.u, v)) return "it does not fit at w";
  if (!fits_at(k.u, v, k.w)) return "it does not fit at u";
  return nullptr;
}

void Sweep::drain_wings() {
  while (!wing_worklist_.empty()) {
    const Vertex v = wing_worklist_.back();
    wing_worklist_.pop_back();
    wing(v, false);
  }
}

// bridge() at a saddle (§4.1 "Bridging the front", Figure 8)

bool Sweep::try_bridge(Index c) {
  const morse::CriticalPoint& cp = ms_.critical[c];
  // Held front edges a -> b with both ends held by c, classified by side of
  // the saddle along its descending direction (sweep-design-notes Q6.1).
  std::vector<Halfedge> side[2];
  for (Vertex v : held_[c]) {
    if (state_[v] != VState::Held || held_by_[v] != c || !mesh_.is_boundary(v)) continue;
    const Halfedge h = mesh_.halfedge(v);
    const Vertex w = mesh_.to_vertex(h);
    if (state_[w] != VState::Held || held_by_[w] != c) continue;
    const double sv = (mesh_.position(v) - cp.position).dot(cp.descent);
    const double sw = (mesh_.position(w) - cp.position).dot(cp.descent);
    if ((sv > 0) != (sw > 0)) continue;
    side[sv > 0 ? 0 : 1].push_back(h);
  }
  if (side[0].empty() || side[1].empty()) return false;
  // True if the front path from vertex x to vertex y (along next) leaves the
  // hold region of c; false if it stays inside it or does not reach y (y is
  // on another boundary loop).
  auto path_leaves = [&](Vertex x, Vertex y, bool& same_loop) {
    Halfedge h = mesh_.halfedge(x);
    bool left = false;
    for (std::size_t guard = 0; guard < mesh_.n_halfedges(); ++guard) {
      const Vertex z = mesh_.from_vertex(h);
      if (z == y) {
        same_loop = true;
        return left;
      }
      if (!(state_[z] == VState::Held && held_by_[z] == c)) left = true;
      h = mesh_.next(h);
      if (mesh_.from_vertex(h) == x) break;
    }
    same_loop = false;
    return left;
  };
  // The pair with the closest midpoints among the admissible ones: on two
  // different loops (merge), or on one loop with both connecting paths
  // leaving the hold region (split): a bowl or a front piece that straddles
  // the saddle's descending plane inside the region is one side, not two.
  double best = std::numeric_limits<double>::infinity();
  Halfedge ba, bc;
  for (Halfedge h0 : side[0])
    for (Halfedge h1 : side[1]) {
      const Vertex a = mesh_.from_vertex(h0), b = mesh_.to_vertex(h0);
      const Vertex cc = mesh_.from_vertex(h1), d = mesh_.to_vertex(h1);
      if (a == cc || a == d || b == cc || b == d) continue;
      const double dist =
          (0.5 * (mesh_.position(a) + mesh_.position(b)) - 0.5 * (mesh_.position(cc) + mesh_.position(d))).norm();
      if (dist >= best) continue;
      // The quad a b c d must be convex in T_s, and the rails a-d, b-c must
      // enter the hole wedges at a, b, c, d (sweep-design-notes Q6.2).
      if (!quad_fits(a, b, cc, d, cp.position, cp.sigma * e_)) continue;
      bool same = false;
      const bool leaves1 = path_leaves(b, cc, same);
      if (same) {
        bool same2 = false;
        if (!leaves1 || !path_leaves(d, a, same2)) continue;
      }
      best = dist, ba = h0, bc = h1;
    }
  if (!ba.is_valid()) return false;
  const Vec3 ga = 0.5 * (mesh_.position(mesh_.from_vertex(ba)) + mesh_.position(mesh_.to_vertex(ba)));
  const Vec3 gc = 0.5 * (mesh_.position(mesh_.from_vertex(bc)) + mesh_.position(mesh_.to_vertex(bc)));
  const double ell = opt_.disc_factor * cp.rho;
  bridge(ba, bc, c, std::max(1, static_cast<int>(std::lround((ga - gc).norm() / ell))));
  return true;
}

bool Sweep::try_contact(Vertex v, const Corner& k) {
  const double r = disc_radius(v);
  const Vec3 pv = mesh_.position(v), n = normal_[v];
  // Vertices within 2 hops along the front are the wing's business.
  std::array<Vertex, 4> near_hops;
  {
    Halfedge f = k.out, b = k.in;
    for (int i = 0; i < 2; ++i) {
      near_hops[i] = mesh_.to_vertex(f);
      near_hops[2 + i] = mesh_.from_vertex(b);
      f = mesh_.next(f), b = mesh_.prev(b);
    }
  }
  const double margin = 15.0 * kDeg;
  Vertex best;
  double best_d = std::numeric_limits<double>::infinity();
  vertex_grid_->for_each_near(pv, 1.5 * r, [&](Index xi, const Vec3& px) {
    const Vertex x(xi);
    if (x == v || state_[x] == VState::Interior || mesh_.is_deleted(x) || mesh_.is_isolated(x) ||
        !mesh_.is_boundary(x))
      return;
    if (std::find(near_hops.begin(), near_hops.end(), x) != near_hops.end()) return;
    if (normal_[x].dot(n) <= 0.5) return;
    const double a = ccw_angle(k.dw, tangent_dir(pv, n, px), n);
    if (!(a > margin && a < k.angle - margin)) return;
    const Corner kx = corner(x);
    const double ax = ccw_angle(kx.dw, tangent_dir(px, normal_[x], pv), normal_[x]);
    if (trace_)
      tracef("contact candidate v%u for v%u: a %.1f of %.1f, ax %.1f of %.1f\n", x.idx(), v.idx(), a / kDeg,
                   k.angle / kDeg, ax / kDeg, kx.angle / kDeg);
    if (!(ax > margin && ax < kx.angle - margin)) return;
    const double d = (px - pv).norm();
    if (d < best_d) best_d = d, best = x;
  });
  if (!best.is_valid()) return false;
  if (holder_of(best) != kInvalidIndex) {
    hold(v, holder_of(best));
    return true;
  }
  return contact_with(v, k, best);
}

bool Sweep::quad_fits(Vertex a, Vertex b, Vertex c, Vertex d, const Vec3& origin, const Vec3& normal) const {
  const Vec3 t1 = normal.unitOrthogonal(), t2 = normal.cross(t1);
  std::array<std::array<double, 2>, 4> P;
  const Vertex q[4] = {a, b, c, d};
  for (int i = 0; i < 4; ++i) {
    const Vec3 dd = mesh_.position(q[i]) - origin;
    P[i] = {dd.dot(t1), dd.dot(t2)};
  }
  for (int i = 0; i < 4; ++i)
    if (geometry::orient2d(P[i][0], P[i][1], P[(i + 1) % 4][0], P[(i + 1) % 4][1], P[(i + 2) % 4][0],
                           P[(i + 2) % 4][1]) != Sign::Positive)
      return false;
  // Counter-clockwise quad a b c d: at a the new triangles span from b to d,
  // at b from c to a, at c from d to b, at d from a to c.
  return fits_at(a, b, d) && fits_at(b, c, a) && fits_at(c, d, b) && fits_at(d, a, c);
}

bool Sweep::contact_with(Vertex v, const Corner& k, Vertex best) {
  const Vec3 pv = mesh_.position(v), n = normal_[v];
  // Two ways to join: v->w with x_u->x (quad v w x_u x), or u->v with x->x_w
  // (quad u v x x_w). Take the convex one that fits at its four corners, with
  // the better minimum angle.
  const Halfedge xo = mesh_.halfedge(best);
  const Halfedge cand[2][2] = {{k.out, mesh_.prev(xo)}, {k.in, xo}};
  double best_q = -1;
  int pick = -1;
  for (int o = 0; o < 2; ++o) {
    const Vertex a = mesh_.from_vertex(cand[o][0]), b = mesh_.to_vertex(cand[o][0]);
    const Vertex c = mesh_.from_vertex(cand[o][1]), d = mesh_.to_vertex(cand[o][1]);
    if (a == c || a == d || b == c || b == d) continue;
    if (mesh_.find_halfedge(b, c).is_valid() || mesh_.find_halfedge(d, a).is_valid() ||
        mesh_.find_halfedge(a, c).is_valid() || mesh_.find_halfedge(b, d).is_valid())
      continue;
    if (!quad_fits(a, b, c, d, pv, n)) continue;
    const Vec3 pa = mesh_.position(a), pb = mesh_.position(b), pc = mesh_.position(c), pd = mesh_.position(d);
    const double qual = std::max(std::min(min_angle(pa, pb, pc), min_angle(pc, pd, pa)),
                                 std::min(min_angle(pa, pb, pd), min_angle(pb, pc, pd)));
    if (qual > best_q) best_q = qual, pick = o;
  }
  if (pick < 0) return false;
  if (trace_)
    tracef("contact v%u with v%u (dist %.3f)\n", v.idx(), best.idx(), (mesh_.position(best) - pv).norm());
  bridge(cand[pick][0], cand[pick][1], kInvalidIndex, 1);
  ++stats_.contacts;
  return true;
}

bool Sweep::release_saddles() {
  bool any = false;
  for (std::size_t c = 0; c < ms_.critical.size(); ++c) {
    if (!ms_.live[c] || ms_.critical[c].kind != CriticalKind::Saddle || resolved_[c]) continue;
    resolved_[c] = 1;
    ++stats_.released;
    for (Vertex v : held_[c])
      if (state_[v] == VState::Held && held_by_[v] == c) {
        state_[v] = VState::Front;
        held_by_[v] = kInvalidIndex;
        if (mesh_.is_boundary(v)) push(v), any = true;
      }
    held_[c].clear();
  }
  return any;
}

void Sweep::bridge(Halfedge ab, Halfedge cd, Index c, int rows) {
  const Vertex a = mesh_.from_vertex(ab), b = mesh_.to_vertex(ab);
  const Vertex cv = mesh_.from_vertex(cd), d = mesh_.to_vertex(cd);
  // Ladder of k rows across the gap (sweep-design-notes Q6.2): left rail a -> d,
  // right rail b -> c, intermediate points pulled back onto the skin.
  const Vec3 pa = mesh_.position(a), pb = mesh_.position(b), pc = mesh_.position(cv), pd = mesh_.position(d);
  if (trace_)
    tracef("bridge saddle %d: a v%u b v%u c v%u d v%u rows %d\n", int(c), a.idx(), b.idx(), cv.idx(),
                 d.idx(), rows);
  std::vector<Vertex> L{a}, R{b};
  for (int j = 1; j < rows; ++j) {
    const double t = double(j) / rows;
    Index cl = cell_[a], cr = cell_[b];
    const Vec3 ql = skin_.pull_back((1 - t) * pa + t * pd, cl);
    const Vec3 qr = skin_.pull_back((1 - t) * pb + t * pc, cr);
    L.push_back(new_vertex(ql, cl));
    R.push_back(new_vertex(qr, cr));
  }
  L.push_back(d);
  R.push_back(cv);
  for (int j = 1; j <= rows; ++j) {
    const Vertex l0 = L[j - 1], r0 = R[j - 1], r1 = R[j], l1 = L[j];
    // Quad l0 r0 r1 l1 (counter-clockwise): split by the diagonal with the
    // better minimum angle.
    const double d1 = std::min(min_angle(mesh_.position(l0), mesh_.position(r0), mesh_.position(r1)),
                               min_angle(mesh_.position(r1), mesh_.position(l1), mesh_.position(l0)));
    const double d2 = std::min(min_angle(mesh_.position(l0), mesh_.position(r0), mesh_.position(l1)),
                               min_angle(mesh_.position(r0), mesh_.position(r1), mesh_.position(l1)));
    if (d1 >= d2) {
      add_triangle(l0, r0, r1);
      add_triangle(r1, l1, l0);
    } else {
      add_triangle(l0, r0, l1);
      add_triangle(r0, r1, l1);
    }
  }
  if (c != kInvalidIndex) {
    stats_.bridge_rows += rows;
    ++stats_.bridges;
    resolved_[c] = 1;
    // Release the vertices held by c.
    for (Vertex v : held_[c])
      if (state_[v] == VState::Held && held_by_[v] == c) {
        state_[v] = VState::Front;
        held_by_[v] = kInvalidIndex;
      }
    held_[c].clear();
  }
  for (std::size_t j = 0; j < L.size(); ++j)
    for (Vertex v : {L[j], R[j]})
      if (mesh_.is_boundary(v) && state_[v] != VState::Interior) state_[v] = VState::Front;
  for (Vertex v : mesh_.vertices())
    if (state_[v] == VState::Front && mesh_.is_boundary(v) && !mesh_.is_isolated(v)) {
      // Re-push everything near the saddle (cheap: lazy deletion).
      if (c != kInvalidIndex && (mesh_.position(v) - ms_.critical[c].position).norm() < 3 * ms_.protect_radius[c])
        push(v);
    }
  if (c == kInvalidIndex)
    for (Vertex v : {a, b, cv, d})
      if (state_[v] == VState::Front && mesh_.is_boundary(v)) push(v);
  for (Vertex v : {a, b, cv, d}) {
    if (mesh_.is_boundary(v) && state_[v] == VState::Front) wing_worklist_.push_back(v);
    if (!mesh_.is_boundary(v)) state_[v] = VState::Interior;
  }
  for (std::size_t j = 1; j + 1 < L.size(); ++j)
    for (Vertex v : {L[j], R[j]})
      if (!mesh_.is_boundary(v)) state_[v] = VState::Interior;
}

// seal() the holes at maxima (§4.1 "Sealing holes")

bool Sweep::small_hole(Vertex v) const {
  const double reach = 2.5 * disc_radius(v);
  const Halfedge start = mesh_.halfedge(v);
  Halfedge h = start;
  double angle_sum = 0;
  for (int count = 1; count <= 7; ++count) {
    const Vertex x = mesh_.to_vertex(h);
    angle_sum += corner(x).angle;
    // A loop of k vertices bounds a small hole (not the outside of a small
    // disc, like a fresh bowl) iff its hole angles add up to (k - 2) 180°.
    if (x == v) return angle_sum < count * kPi;
    if ((mesh_.position(x) - mesh_.position(v)).norm() > reach) return false;
    h = mesh_.next(h);
  }
  return false;
}

void Sweep::seal_all() {
  const std::size_t max_loops = mesh_.n_halfedges() + 1;
  for (std::size_t iter = 0;; ++iter) {
    if (iter > max_loops) throw TopologyError("seal: the holes do not close");
    Halfedge start;
    for (Vertex v : mesh_.vertices())
      if (!mesh_.is_deleted(v) && !mesh_.is_isolated(v) && mesh_.is_boundary(v)) {
        start = mesh_.halfedge(v);
        break;
      }
    if (!start.is_valid()) return;
    seal_loop(start);
  }
}

bool Sweep::fill_hole_dp(const std::vector<Vertex>& poly) {
  const std::size_t k = poly.size();
  const double kNone = -1;
  // q[i][j]: best minimum angle of a triangulation of the sub-polygon
  // poly[i..j] closed by the diagonal (i, j); arg[i][j]: its apex.
  std::vector<double> q(k * k, kNone);
  std::vector<std::size_t> arg(k * k, k);
  auto at = [k](std::size_t i, std::size_t j) { return i * k + j; };
  auto diagonal_ok = [&](std::size_t i, std::size_t j) {
    if (j == i + 1 || (i == 0 && j == k - 1)) return true;  // a hole edge
    return !mesh_.find_halfedge(poly[i], poly[j]).is_valid();
  };
  auto tri_quality = [&](std::size_t i, std::size_t m, std::size_t j) {
    const Vec3 &a = mesh_.position(poly[i]), &b = mesh_.position(poly[m]), &c = mesh_.position(poly[j]);
    const Vec3 nt = (b - a).cross(c - a);
    if (nt.dot(normal_[poly[i]]) <= 0 || nt.dot(normal_[poly[m]]) <= 0 || nt.dot(normal_[poly[j]]) <= 0) return kNone;
    // Each corner's span must lie in that vertex's hole wedge (no overlap
    // with the triangles already there).
    if (!fits_at(poly[i], poly[m], poly[j]) || !fits_at(poly[m], poly[j], poly[i]) ||
        !fits_at(poly[j], poly[i], poly[m]))
      return kNone;
    return min_angle(a, b, c);
  };
  for (std::size_t i = 0; i + 1 < k; ++i) q[at(i, i + 1)] = kPi;  // an edge: nothing to fill
  for (std::size_t len = 2; len < k; ++len)
    for (std::size_t i = 0; i + len < k; ++i) {
      const std::size_t j = i + len;
      if (!diagonal_ok(i, j)) continue;
      for (std::size_t m = i + 1; m < j; ++m) {
        const double sub = std::min(q[at(i, m)], q[at(m, j)]);
        if (sub <= q[at(i, j)]) continue;
        const double t = std::min(sub, tri_quality(i, m, j));
        if (t > q[at(i, j)]) q[at(i, j)] = t, arg[at(i, j)] = m;
      }
    }
  if (q[at(0, k - 1)] <= 0) return false;
  std::vector<std::array<std::size_t, 2>> stack{{0, k - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j == i + 1) continue;
    const std::size_t m = arg[at(i, j)];
    add_triangle(poly[i], poly[m], poly[j]);
    stack.push_back({i, m});
    stack.push_back({m, j});
  }
  for (Vertex v : poly) state_[v] = VState::Interior;
  ++stats_.seals;
  return true;
}

Halfedge Sweep::enlarge_hole(const std::vector<Vertex>& poly) {
  std::vector<Vertex> rim;  // surviving corners of the deleted faces
  // Deletes every face around the vertices `around`; their corners that keep
  // a face join the rim.
  auto delete_faces_around = [&](const std::vector<Vertex>& around) {
    std::vector<Face> faces;
    for (Vertex v : around)
      for (Face f : mesh_.faces(v))
        if (std::find(faces.begin(), faces.end(), f) == faces.end()) faces.push_back(f);
    std::vector<Vertex> corners;
    for (Face f : faces)
      for (Vertex x : mesh_.vertices(f)) corners.push_back(x);
    for (Face f : faces) mesh_.delete_face(f);
    for (Vertex x : corners)
      if (!mesh_.is_deleted(x) && !mesh_.is_isolated(x)) rim.push_back(x);
  };
  auto gaps = [&](Vertex x) {
    int n = 0;
    for (Halfedge h : mesh_.halfedges(x)) n += mesh_.is_boundary(h);
    return n;
  };
  delete_faces_around(poly);
  ++stats_.enlarged_holes;
  // A pinched vertex (two boundary gaps) cannot be handled by the front:
  // delete its remaining faces too, a few times at most.
  for (int round = 0; round < 4; ++round) {
    std::vector<Vertex> pinched;
    for (Vertex x : rim)
      if (!mesh_.is_deleted(x) && !mesh_.is_isolated(x) && gaps(x) > 1) pinched.push_back(x);
    if (pinched.empty()) break;
    delete_faces_around(pinched);
  }
  Halfedge start;
  for (Vertex x : rim) {
    if (mesh_.is_deleted(x) || mesh_.is_isolated(x)) continue;
    if (gaps(x) != 1) return Halfedge();
    state_[x] = VState::Front;
    start = mesh_.halfedge(x);
  }
  return start;
}

void Sweep::seal_loop(Halfedge start, int depth_left) {
  std::vector<Halfedge> loop = mesh_.boundary_loop(start);
  std::vector<Vertex> poly;
  for (Halfedge h : loop) poly.push_back(mesh_.to_vertex(h));
  if (poly.size() <= 40 && fill_hole_dp(poly)) return;
  // Plane of projection: the first of (the average vertex normal, the normal
  // of the best-fit plane, each vertex normal) in which the hole is a simple,
  // counter-clockwise polygon. A hole with a narrow waist can cross itself in
  // the average plane.
  Vec3 centre = Vec3::Zero(), nbar = Vec3::Zero();
  for (Vertex v : poly) centre += mesh_.position(v), nbar += normal_[v];
  centre /= double(poly.size());
  if (nbar.norm() == 0) throw TopologyError("seal: hole with a degenerate average normal");
  nbar.normalize();
  std::vector<Vec3> planes{nbar};
  {
    Mat3 cov = Mat3::Zero();
    for (Vertex v : poly) {
      const Vec3 d = mesh_.position(v) - centre;
      cov += d * d.transpose();
    }
    Eigen::SelfAdjointEigenSolver<Mat3> es(cov);
    Vec3 pn = es.eigenvectors().col(0);
    planes.push_back(pn.dot(nbar) < 0 ? Vec3(-pn) : pn);
    for (Vertex v : poly) planes.push_back(normal_[v]);
  }
  Vec3 n, t1, t2;
  auto proj = [&](Vertex v) {
    const Vec3 d = mesh_.position(v) - centre;
    return std::array<double, 2>{d.dot(t1), d.dot(t2)};
  };
  auto simple_ccw = [&]() {
    const std::size_t k = poly.size();
    std::vector<std::array<double, 2>> P(k);
    double area2 = 0;
    for (std::size_t i = 0; i < k; ++i) P[i] = proj(poly[i]);
    for (std::size_t i = 0; i < k; ++i) area2 += P[i][0] * P[(i + 1) % k][1] - P[(i + 1) % k][0] * P[i][1];
    if (!(area2 > 0)) return false;
    auto o = [&](std::size_t a, std::size_t b, std::size_t c) {
      return geometry::orient2d(P[a][0], P[a][1], P[b][0], P[b][1], P[c][0], P[c][1]);
    };
    for (std::size_t i = 0; i < k; ++i)
      for (std::size_t j = i + 1; j < k; ++j) {
        const std::size_t i1 = (i + 1) % k, j1 = (j + 1) % k;
        if (j == i1 || i == j1) continue;  // adjacent edges
        const Sign s1 = o(i, i1, j), s2 = o(i, i1, j1), s3 = o(j, j1, i), s4 = o(j, j1, i1);
        if (s1 != s2 && s3 != s4) return false;  // the edges touch or cross
      }
    return true;
  };
  bool found = false;
  for (const Vec3& cand : planes) {
    if (cand.dot(nbar) <= 0.3) continue;
    n = cand;
    t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    if ((found = simple_ccw())) break;
  }
  if (!found) {
    std::ostringstream os;
    os << "seal: the hole of " << poly.size() << " vertices near (" << centre.transpose()
       << ") is not a simple polygon in any plane tried";
    if (depth_left > 0) {
      if (trace_) tracef("%s: enlarging it\n", os.str().c_str());
      const Halfedge h = enlarge_hole(poly);
      if (h.is_valid()) {
        seal_loop(h, depth_left - 1);
        return;
      }
      os << "; enlarging it pinched the front";
    }
    throw TopologyError(os.str());
  }
  if (trace_) {
    std::ostringstream os;
    os << "seal loop of " << poly.size() << ":";
    for (Vertex x : poly) {
      const auto px = proj(x);
      os << " v" << x.idx() << "[" << px[0] << "," << px[1] << "|hole " << corner(x).angle / kDeg << "]";
    }
    opt_.trace(os.str());
  }
  // Ear clipping: the hole is on the left of u -> v -> w; an ear at v is a
  // left turn with no other polygon vertex inside; take the best 3D angle.
  bool strict = true;  // ears must fit the hole wedges; relaxed when no ear does
  while (poly.size() > 3) {
    const std::size_t k = poly.size();
    double best = -1;
    std::size_t bi = k;
    for (std::size_t i = 0; i < k; ++i) {
      const Vertex u = poly[(i + k - 1) % k], v = poly[i], w = poly[(i + 1) % k];
      const auto pu = proj(u), pv = proj(v), pw = proj(w);
      if (geometry::orient2d(pu[0], pu[1], pv[0], pv[1], pw[0], pw[1]) != Sign::Positive) continue;
      if (mesh_.find_halfedge(w, u).is_valid()) continue;
      bool empty = true;
      for (std::size_t j = 0; j < k && empty; ++j) {
        const Vertex x = poly[j];
        if (x == u || x == v || x == w) continue;
        const auto px = proj(x);
        if (geometry::orient2d(pu[0], pu[1], pv[0], pv[1], px[0], px[1]) != Sign::Negative &&
            geometry::orient2d(pv[0], pv[1], pw[0], pw[1], px[0], px[1]) != Sign::Negative &&
            geometry::orient2d(pw[0], pw[1], pu[0], pu[1], px[0], px[1]) != Sign::Negative)
          empty = false;
      }
      if (!empty) continue;
      // The ear must also face outwards at its three corners (a sliver across
      // a narrow waist can turn over between the projection plane and T_x).
      const Vec3 nt = (mesh_.position(w) - mesh_.position(v)).cross(mesh_.position(u) - mesh_.position(v));
      if (nt.dot(normal_[u]) <= 0 || nt.dot(normal_[v]) <= 0 || nt.dot(normal_[w]) <= 0) continue;
      if (strict && (!fits_at(u, v, w) || !fits_at(v, w, u) || !fits_at(w, u, v))) continue;
      const double q = min_angle(mesh_.position(u), mesh_.position(v), mesh_.position(w));
      if (q > best) best = q, bi = i;
    }
    if (bi == k && strict) {
      strict = false;
      continue;
    }
    if (bi == k) {
      std::ostringstream os;
      os << "seal: no ear in a hole of " << k << " vertices near (" << centre.transpose() << "):";
      for (Vertex x : poly) {
        const auto px = proj(x);
        os << " [" << px[0] << "," << px[1] << "]";
      }
      throw TopologyError(os.str());
    }
    const Vertex u = poly[(bi + k - 1) % k], v = poly[bi], w = poly[(bi + 1) % k];
    if (trace_) tracef("  ear v%u v%u v%u\n", u.idx(), v.idx(), w.idx());
    add_triangle(v, w, u);
    state_[v] = VState::Interior;
    poly.erase(poly.begin() + static_cast<std::ptrdiff_t>(bi));
  }
  add_triangle(poly[0], poly[1], poly[2]);
  for (Vertex v : poly) state_[v] = VState::Interior;
  ++stats_.seals;
}

// The sweep (Algorithm 1)

void Sweep::hold(Vertex v, Index c) {
  state_[v] = VState::Held;
  held_by_[v] = c;
  held_[c].push_back(v);
  ++stats_.held;
  const std::size_t f0 = mesh_.faces_size();
  if (ms_.critical[c].kind == CriticalKind::Saddle && try_bridge(c)) paranoid_check(f0, "bridge");
  const std::size_t f1 = mesh_.faces_size();
  drain_wings();
  paranoid_check(f1, "wings after a hold");
}

SweepResult Sweep::run() {
  // Initial front: a bowl at every live minimum.
  for (std::size_t c = 0; c < ms_.critical.size(); ++c)
    if (ms_.live[c] && ms_.critical[c].kind == CriticalKind::Minimum) creation(static_cast<Index>(c));

  // Creeping triangles.
  const long max_steps = opt_.max_steps;
  long steps = 0;
  for (;;) {
  while (!queue_.empty()) {
    if (max_steps >= 0 && steps++ >= max_steps) {
      if (!opt_.dump_path.empty()) geometry::write_mesh(opt_.dump_path, mesh_.to_indexed_mesh());
      throw TopologyError("stopped after max_steps departures");
    }
    const QueueEntry top = queue_.top();
    queue_.pop();
    ++step_;
    const Vertex v(top.v);
    if (top.stamp != stamp_[v] || state_[v] != VState::Front || mesh_.is_deleted(v) || mesh_.is_isolated(v) ||
        !mesh_.is_boundary(v))
      continue;
    const Index c = hold_region(v);
    if (c != kInvalidIndex) {
      hold(v, c);
      continue;
    }
    const std::size_t f0 = mesh_.faces_size();
    if (small_hole(v)) {
      // A small hole (at most 6 front vertices within 2.5 r of v): the fronts
      // around it have met; close it now, as seal() would (sweep-design-notes
      // Q2.3), instead of creeping new vertices into it.
      seal_loop(mesh_.halfedge(v));
      paranoid_check(f0, "closing a small hole");
      continue;
    }
    creep(v);
    paranoid_check(f0, "creep");
    const std::size_t f1 = mesh_.faces_size();
    drain_wings();
    paranoid_check(f1, "wings after a creep");
  }
  // Saddles never bridged (the front reached them from one side only, or the
  // two sides met elsewhere by a contact): release their holds and go on
  // (sweep-design-notes Q6.4); the final topology check decides.
  if (!release_saddles()) break;
  }

  if (!opt_.dump_path.empty()) geometry::write_mesh(opt_.dump_path, mesh_.to_indexed_mesh());
  seal_all();

  if (opt_.refine) {
    refine::RefineOptions ro;
    ro.size = opt_.size;
    const refine::RefineStats rs = refine::refine_mesh(skin_, mesh_, ro);
    stats_.flips = rs.flips;
    stats_.contractions = rs.contractions;
    stats_.insertions = rs.insertions;
    stats_.refine_rounds = rs.rounds;
    stats_.L_left = rs.L_left;
    stats_.U_left = rs.U_left;
  }

  SweepResult res;
  mesh_.garbage_collection();
  res.mesh = mesh_.to_indexed_mesh();
  res.mesh.normals.resize(res.mesh.positions.size());
  res.mesh.atom.resize(res.mesh.positions.size());
  Index i = 0;
  for (Vertex v : mesh_.vertices()) {
    res.mesh.normals[i] = normal_[v];
    res.mesh.atom[i] = static_cast<std::int32_t>(skin_.atom_of(cell_[v], mesh_.position(v)));
    ++i;
  }
  res.stats = stats_;
  return res;
}

}  // namespace

SweepResult sweep_mesh(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms,
                       const SweepOptions& opt) {
  Sweep sweep(skin, ms, opt);
  return sweep.run();
}

}  // namespace skinmesh::front

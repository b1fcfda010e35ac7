// refine/angle_improvement.cpp: vertex moves that raise the smallest angles
// while keeping [L], [U], the restricted Delaunay property and the embedding.
// Notes: papers/refine/angle_improvement.md
#include "refine/angle_improvement.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "geometry/check/mesh_checks.h"
#include "geometry/kernel/triangle_intersection.h"
#include "geometry/triangulation/point_grid.h"
#include "skin/restricted_delaunay.h"
#include "skin/vertex_data.h"

namespace skinmesh::refine {

using geometry::Face;
using geometry::Halfedge;
using geometry::min_angle;
using geometry::SurfaceMesh;
using geometry::Vertex;
using Vec2 = Eigen::Vector2d;

namespace {

constexpr double kSqrt5 = 2.2360679774997896964;
/// The pass runs only if every triangle has R <= kMaxKappa · rho_min: then
/// 2 sqrt(5) kappa <= 0.895 < 1 and the neighbourhood radius of
/// papers/refine/angle_improvement.md ("Which triangles a move can affect")
/// is finite. [U] gives kappa < CQ = 0.132.
constexpr double kMaxKappa = 0.2;
/// Triangles per block of scan() on the threads. [chosen] large enough that
/// a block's hand-out and its share of the join cost little beside its tests.
constexpr std::size_t kScanGrain = 16384;
/// Angles within this of the star's minimum are active in the ascent
/// (radians; 0.25°): their gradients together decide the direction, so the
/// ascent does not zigzag between nearly equal angles. [chosen]
constexpr double kActiveBand = 0.25 * kDegree;
/// Halvings of an ascent step before the ascent stops. [chosen]
constexpr int kMaxHalvings = 6;
/// Positions of the ascent offered to the full check, best first, per
/// attempt, and then shorter moves along the best one (1/4, 1/8, 1/16 of it).
/// [measured: on hivprotease at probe 0 the shorter moves turn 62 refused
/// attempts into 12]
constexpr int kMaxChecked = 6;
constexpr std::size_t kShorterMoves = 3;

/// Relative and absolute (times L) padding of the neighbourhood bounds, far
/// above the rounding of the quantities they bound and far below anything
/// that changes which vertices they admit in practice.
constexpr double kBoundPad = 1e-6;
constexpr double kBoundPadL = 1e-9;
/// Relative rounding allowance of reach() over its closed form. [derived]
/// above the rounding of a few products and quotients.
constexpr double kReachRounding = 1e-12;
/// Octaves of rho per level of the neighbourhood grids (as the sweep's
/// grids, front/front_state.h). [measured]
constexpr int kGridOctaves = 2;
/// Cells of the bitmap that selects a pass's static grid (build_static_grid):
/// at most this many, 16 MiB of bits. [chosen] far more than the boxes of
/// the candidates' neighbourhoods need at their median radius.
constexpr double kMaxCoverCells = double(std::uint64_t{1} << 27);
/// Cells the candidates' boxes may mark in all, per candidate: the bitmap's
/// cells grow until the marks cost at most this, so that a candidate whose
/// reach is far above the median (a thin neck among ordinary patches) does
/// not mark its box cell by cell. [chosen] a few times the 27 cells of a
/// box about the median radius.
constexpr double kMarksPerCandidate = 128;
/// Smallest rho (Å) a grid cell is scaled by: a guard for degenerate skins.
/// [derived] far below any vertex's rho.
constexpr double kMinScale = 1e-9;
/// The normal-line projection of a trial position searches within these
/// multiples of the sandwiching balls' bracket rho - sqrt(rho² - r²): twice
/// it, then eight times. [derived] the bracket itself (papers/skin/skin_math.md
/// §7.2), doubled for the balls' own rounding; the wider search catches the
/// rare trial where rho changes fast between the vertex and its target.
constexpr double kProjectionBrackets[] = {2.0, 8.0};
/// Relative and absolute (times L) slack of that search distance. [derived]
/// the root finder's margin (skin::SkinSurface::project_along_line), rounded up.
constexpr double kProjectionSlack = 1e-9;
constexpr double kProjectionSlackL = 1e-12;

/// A triangle that does not move during an attempt: corners, circumcentre,
/// circumradius, and its surface Delaunay ball once computed.
struct FaceGeometry {
  std::array<Index, 3> v;
  Vec3 cc;
  double R;
  /// The surface Delaunay ball: not computed yet, computed (m, r), or none
  /// (the dual line misses the skin).
  enum class Ball : std::uint8_t { NotComputed, Valid, None } ball = Ball::NotComputed;
  Vec3 m = Vec3::Zero();
  double r = 0;
};

/// One position tried by the ascent.
struct Trial {
  Vec2 x = Vec2::Zero();                                ///< tangent-plane offset from the start (Å)
  Vec3 p = Vec3::Zero();                                ///< its projection onto the skin (Å)
  skin::SkinSample s;                                   ///< the skin at p (normal, rho, cell)
  double q = -std::numeric_limits<double>::infinity();  ///< star minimum angle at p (radians)
};

/// Why a trial position was refused (the first condition it broke).
enum class Refusal { None, Orientation, L, U, Rdt, Intersection };

class AngleImprover {
 public:
  AngleImprover(const skin::SkinSurface& skin, SurfaceMesh& mesh, const AngleImprovementOptions& opt,
                const skin::SizeConstants& size, int threads)
      : skin_(skin), mesh_(mesh), opt_(opt), size_(size), L_(skin.length_scale()), threads_(threads) {
    cell_ = mesh_.vertex_property(skin::kVertexCell, kInvalidIndex);
    for (Vertex v : mesh_.vertices())
      if (cell_[v] == kInvalidIndex) cell_[v] = skin_.sample(mesh_.position(v)).cell;
    normal_ = skin::VertexNormals(skin_.mixed_complex(), mesh_);
    rho_ = skin::VertexRhos(skin_.mixed_complex(), mesh_);
  }

  AngleImprovementStats run();

 private:
  /// What a move of vertex v may affect: v moves at most M in its tangent
  /// plane, its ring lies within S of it (papers/refine/angle_improvement.md,
  /// "Which triangles a move can affect").
  struct Bounds {
    Vertex v;
    double M, S;
  };

  const Vec3& pos(Vertex v) const { return mesh_.position(v); }
  /// The one-ring of v, counter-clockwise; false if v is on a boundary or
  /// its star is not a simple fan of at least three triangles.
  bool ring_of(Vertex v, std::vector<Vertex>& ring) const;
  /// Smallest angle (radians) of the star of a vertex at p with this ring.
  double star_min(const Vec3& p, const std::vector<Vertex>& ring) const;
  /// Smallest angle (radians) of triangle f, by min_angle().
  double face_min_angle(Face f) const;
  /// Scans every triangle: returns the smallest angle (degrees, by
  /// min_angle(), the verifier's formula), appends the triangles below the
  /// target to *low, sets *worst_high to the triangle with the smallest
  /// angle among the others and *kappa to max(CQ, max R / rho_min).
  double scan(std::vector<Face>* low, double* kappa, Face* worst_high);
  /// False if a vertex at distance d (Å) from b.v, with local length scale
  /// rho_x (Å), can neither be a corner of a triangle that the move affects
  /// nor lie in a star triangle's surface ball.
  bool relevant(const Bounds& b, double d, double rho_x) const;
  /// The distance (Å) from b.v within which a vertex of local length scale
  /// rho_x (Å) is relevant(); increasing in rho_x.
  double relevance_radius(const Bounds& b, double rho_x) const;
  /// Radius (Å) about b.v that holds every relevant() vertex, rho being
  /// 1-Lipschitz.
  double reach(const Bounds& b) const;
  /// The relevant() vertices of a move of b.v, b.v excluded: the static grid
  /// for the vertices that never moved, the grid of moved vertices for the
  /// others.
  std::vector<Vertex> neighbourhood(const Bounds& b) const;
  /// Makes grid_ for a pass whose candidates are `cands`: every vertex
  /// that has not moved and lies within covered_[c] of a candidate c (and
  /// some farther ones), in index order. The pass's queries read only those:
  /// the grid follows the candidates, not the mesh.
  void build_static_grid(const std::vector<std::pair<double, Vertex>>& cands);
  /// Moves v to a better admissible position if there is one.
  bool try_improve(Vertex v);
  /// Projects the tangent-plane offset x onto the skin along n0 and
  /// evaluates the star there; q stays -inf if the projection fails, leaves
  /// the move bound, folds a star triangle over n0, or breaks [L] or [U].
  Trial evaluate(const Vec2& x, Vertex v, const Vec3& n0, const Vec3& t1, const Vec3& t2, double max_offset,
                 const std::vector<Vertex>& ring, Refusal* why) const;
  /// The checks of a trial that evaluate() does not make: orientation with
  /// the skin normal at p, the restricted Delaunay property, embedding.
  Refusal admissible(Vertex v, const Trial& t, const std::vector<Vertex>& ring, const std::vector<Vertex>& nearby,
                     std::vector<FaceGeometry>& faces);
  /// True if x lies inside g's surface Delaunay ball grown by the margin
  /// (or g has no surface ball).
  bool in_ball(FaceGeometry& g, const Vec3& x) const;

  const skin::SkinSurface& skin_;
  SurfaceMesh& mesh_;
  const AngleImprovementOptions& opt_;
  const skin::SizeConstants size_;  ///< C and Q of [L] and [U], kept by every move
  const double L_;
  const int threads_;  ///< for the scans of every triangle (scan())
  double kappa_ = 0;   ///< max R / rho_min over the triangles, at least CQ
  geometry::VertexProperty<Index> cell_;
  skin::VertexNormals normal_;  ///< from the cell
  skin::VertexRhos rho_;        ///< from the cell
  /// The vertices that never moved and lie near a candidate of the pass
  /// (build_static_grid, made again each pass), and the vertices moved
  /// since the pass began at their new positions. Both are leveled by the
  /// vertices' rho, a level's cells half the median reach over rho of the
  /// first candidates times the level's scale: a query reads cells of its
  /// own scale, whatever the scales of the other candidates
  /// (papers/refine/angle_improvement.md). The first holds indices only (4
  /// bytes an entry) and reads the mesh's positions: a vertex that never
  /// moved is where it was, and a moved one is skipped there (moved_) and
  /// found in the second. The mesh gains no vertex here, so the positions
  /// stay where the grid reads them.
  std::optional<geometry::LeveledIndexGrid> grid_;
  std::optional<geometry::LeveledPointGrid> moved_grid_;
  double cell_per_scale_ = 0;        ///< of both grids, from the first pass's candidates
  std::vector<std::uint8_t> moved_;  ///< per vertex: 1 once it has moved
  std::vector<Face> touched_;        ///< the stars of the moved vertices
  /// Per candidate of the pass: the radius about it within which grid_
  /// holds every vertex that has not moved (build_static_grid).
  std::unordered_map<Index, double> covered_;
  AngleImprovementStats stats_;
};

bool AngleImprover::ring_of(Vertex v, std::vector<Vertex>& ring) const {
  ring.clear();
  if (mesh_.is_isolated(v)) return false;
  Vertex third_prev;
  for (Halfedge h : mesh_.halfedges(v)) {
    if (mesh_.is_boundary(h)) return false;
    const Vertex u = mesh_.to_vertex(h);
    if (!ring.empty() && third_prev != u) return false;
    ring.push_back(u);
    third_prev = mesh_.to_vertex(mesh_.next(h));
  }
  return ring.size() >= 3 && third_prev == ring.front();
}

double AngleImprover::star_min(const Vec3& p, const std::vector<Vertex>& ring) const {
  double q = std::numeric_limits<double>::infinity();
  const std::size_t k = ring.size();
  for (std::size_t i = 0; i < k; ++i) q = std::min(q, min_angle(p, pos(ring[i]), pos(ring[(i + 1) % k])));
  return q;
}

double AngleImprover::face_min_angle(Face f) const {
  Vec3 x[3];
  int i = 0;
  for (Vertex v : mesh_.vertices(f)) x[i++] = pos(v);
  return min_angle(x[0], x[1], x[2]);
}

double AngleImprover::scan(std::vector<Face>* low, double* kappa, Face* worst_high) {
  // The smallest angle is opposite the shortest edge (squared lengths
  // x <= y, z): cos = (y + z - x) / (2 sqrt(y z)) > 0. Compared through
  // cos² = N² / (4 D), N = y + z - x, D = y z, cross-multiplied: no square
  // root and no division per triangle; the triangles attaining the
  // minima are re-evaluated with min_angle(). This loop touches every
  // triangle, so it reads the raw arrays.
  const double cos_t = std::cos(opt_.target_angle_deg * kDegree);
  const double low_factor = 4 * cos_t * cos_t;  // low iff N² > 4 cos_t² D
  const double CQ2 = size_.C * size_.Q * size_.C * size_.Q;
  const auto& P = mesh_.positions().vector();
  // The smallest rho of all vertices bounds each triangle's rho_min from
  // below: a triangle whose ratio stays within kappa at that bound needs no
  // rho of its own (rounding is monotone, so the skip never drops a triangle
  // the exact comparison below would take).
  double rho_floor = std::numeric_limits<double>::infinity();
  if (kappa) {
    // Each rho is computed from its cell: blocks of vertices on the threads
    // (the smallest value is the same in any order).
    const std::size_t nv = mesh_.vertices_size(), vblocks = (nv + kScanGrain - 1) / kScanGrain;
    std::vector<double> floors(vblocks, std::numeric_limits<double>::infinity());
    parallel_for(vblocks, threads_, 1, [&](std::size_t k) {
      for (std::size_t i = k * kScanGrain, end = std::min(nv, i + kScanGrain); i < end; ++i)
        if (const Vertex v(static_cast<Index>(i)); !mesh_.is_deleted(v)) floors[k] = std::min(floors[k], rho_[v]);
    });
    for (double f : floors) rho_floor = std::min(rho_floor, f);
  }
  // Each block of consecutive faces is scanned on its own and the blocks'
  // results are joined in order, the way one loop would meet them: the
  // result is the same for every thread count.
  struct Block {
    double worst_N2 = -1, worst_D = 1, high_N2 = -1, high_D = 1, kappa2 = 0;
    Face worst, high;
    std::vector<Face> low;
  };
  const std::size_t n = mesh_.faces_size(), blocks = (n + kScanGrain - 1) / kScanGrain;
  std::vector<Block> part(blocks);
  parallel_for(blocks, threads_, 1, [&](std::size_t k) {
    Block& r = part[k];
    r.kappa2 = CQ2;
    for (std::size_t i = k * kScanGrain, end = std::min(n, i + kScanGrain); i < end; ++i) {
      const Face f(static_cast<Index>(i));
      if (mesh_.is_deleted(f)) continue;
      const Halfedge h0 = mesh_.halfedge(f), h1 = mesh_.next(h0);
      const Index i0 = mesh_.to_vertex(h0).idx(), i1 = mesh_.to_vertex(h1).idx(),
                  i2 = mesh_.to_vertex(mesh_.next(h1)).idx();
      const Vec3 &a = P[i0], &b = P[i1], &c = P[i2];
      const double e0 = (b - c).squaredNorm(), e1 = (c - a).squaredNorm(), e2 = (a - b).squaredNorm();
      const double lo01 = std::min(e0, e1), hi01 = std::max(e0, e1);
      const double x = std::min(lo01, e2), y = std::max(lo01, e2), z = hi01;
      const double N = y + z - x, N2 = N * N, D = y * z;
      if (N2 * r.worst_D > r.worst_N2 * D) r.worst_N2 = N2, r.worst_D = D, r.worst = f;
      if (low && N2 > low_factor * D)
        r.low.push_back(f);
      else if (N2 * r.high_D > r.high_N2 * D)
        r.high_N2 = N2, r.high_D = D, r.high = f;
      if (kappa) {
        // R² = e0 e1 e2 / (4 |(b - a) x (c - a)|²) against kappa² rho_min²;
        // the ratio only for triangles beyond the block's kappa so far.
        const double n4 = 4 * (b - a).cross(c - a).squaredNorm();
        const double num = x * y * z;
        if (!(num > n4 * r.kappa2 * rho_floor * rho_floor)) continue;
        const double rmin = std::min(std::min(rho_[Vertex(i0)], rho_[Vertex(i1)]), rho_[Vertex(i2)]);
        if (num > n4 * r.kappa2 * rmin * rmin)
          r.kappa2 = n4 > 0 ? num / (n4 * rmin * rmin) : std::numeric_limits<double>::infinity();
      }
    }
  });
  double worst_N2 = -1, worst_D = 1, high_N2 = -1, high_D = 1, kappa2 = CQ2;
  Face worst;
  for (Block& r : part) {
    if (r.worst.is_valid() && r.worst_N2 * worst_D > worst_N2 * r.worst_D)
      worst_N2 = r.worst_N2, worst_D = r.worst_D, worst = r.worst;
    if (r.high.is_valid() && r.high_N2 * high_D > high_N2 * r.high_D)
      high_N2 = r.high_N2, high_D = r.high_D, *worst_high = r.high;
    if (low) low->insert(low->end(), r.low.begin(), r.low.end());
    kappa2 = std::max(kappa2, r.kappa2);
  }
  if (kappa) *kappa = std::sqrt(kappa2) * (1 + kBoundPad);
  return worst.is_valid() ? face_min_angle(worst) / kDegree : 0.0;
}

bool AngleImprover::relevant(const Bounds& b, double d, double rho_x) const {
  // papers/refine/angle_improvement.md, "Which triangles a move can affect".
  // Positions tried lie within 2M of v, so rho(p) <= rho_v + 2M. A corner
  // a of a triangle whose surface ball holds p, or a vertex in the surface
  // ball of a star triangle, lies within 2 sqrt5 kappa max(rho_a, rho(p))
  // of p; a corner of a triangle meeting the star (radius <= S + 2M about
  // p) lies within S + 2M + 2 kappa rho_a of p.
  return d <= relevance_radius(b, rho_x);
}

double AngleImprover::relevance_radius(const Bounds& b, double rho_x) const {
  const double rho_p = rho_[b.v] + 2 * b.M;
  const double ball = 2 * b.M + 2 * kSqrt5 * kappa_ * std::max(rho_x, rho_p);
  const double cross = 4 * b.M + b.S + 2 * kappa_ * rho_x;
  return std::max(ball, cross) * (1 + kBoundPad) + kBoundPadL * L_;
}

double AngleImprover::reach(const Bounds& b) const {
  // relevant() with rho_x <= rho_v + d (rho is 1-Lipschitz), solved for d:
  // with u = 1 + kBoundPad, l = kBoundPadL L, A = 2 sqrt5 kappa, B = 2 kappa
  // (A u, B u < 1 for kappa <= kMaxKappa),
  //   d <= ((2M + A rho_p) u + l) / (1 - A u)          (ball bound),
  //   d <= ((4M + S + B rho_v) u + l) / (1 - B u)      (crossing bound).
  const double u = 1 + kBoundPad, l = kBoundPadL * L_;
  const double A = 2 * kSqrt5 * kappa_, B = 2 * kappa_;
  const double rho_v = rho_[b.v], rho_p = rho_v + 2 * b.M;
  return std::max(((2 * b.M + A * rho_p) * u + l) / (1 - A * u), ((4 * b.M + b.S + B * rho_v) * u + l) / (1 - B * u)) *
         (1 + kReachRounding);
}

std::vector<Vertex> AngleImprover::neighbourhood(const Bounds& b) const {
  std::vector<Vertex> out;
  const Vec3 p0 = pos(b.v);
  const double r = reach(b);
  // rho is 1-Lipschitz on the skin: the vertices within r have rho within r
  // of rho(v) (padded for rounding). Below rho(v) the bound is tighter: a
  // relevant x with rho_x < rho(v) lies within relevance_radius(b, rho_x)
  // <= R = relevance_radius(b, rho(v)) of v (the radius grows with rho_x),
  // so rho_x >= rho(v) - R. The levels of smaller scales, whose cells are
  // small against the query's reach and which hold vertices from all over
  // the mesh, are not read: the query's cost follows the mesh near v.
  const double rho_v = rho_[b.v], slack = 1e-9 * (rho_v + r);
  const double lo = rho_v - relevance_radius(b, rho_v) - slack, hi = rho_v + r + slack;
  const auto& positions = mesh_.positions().vector();
  const auto covered = covered_.find(b.v.idx());
  if (covered != covered_.end() && r <= covered->second) {
    grid_->for_each_near(p0, r, lo, hi, positions, [&](Index id, const Vec3& p) {
      const Vertex x(id);
      if (x == b.v || moved_[id]) return;
      if (relevant(b, (p - p0).norm(), rho_[x])) out.push_back(x);
    });
  } else {
    // Beyond the static grid's cover, which the bound of build_static_grid
    // rules out: every vertex read, so the neighbourhood is the same.
    for (Vertex x : mesh_.vertices()) {
      if (x == b.v || moved_[x.idx()]) continue;
      const double d = (pos(x) - p0).norm();
      if (d <= r && relevant(b, d, rho_[x])) out.push_back(x);
    }
  }
  moved_grid_->for_each_near(p0, r, lo, hi, positions, [&](Index id, const Vec3& p) {
    const Vertex x(id);
    if (x == b.v) return;
    if (relevant(b, (p - p0).norm(), rho_[x])) out.push_back(x);
  });
  return out;
}

Trial AngleImprover::evaluate(const Vec2& x, Vertex v, const Vec3& n0, const Vec3& t1, const Vec3& t2,
                              double max_offset, const std::vector<Vertex>& ring, Refusal* why) const {
  Trial t;
  t.x = x;
  const Vec3& p0 = pos(v);
  const double rho0 = rho_[v];
  const Vec3 q = p0 + x.x() * t1 + x.y() * t2;
  // Normal-line projection (papers/skin/skin_math.md §7.2): the sandwiching
  // balls of radius rho bracket the skin within rho - sqrt(rho² - r²) of the
  // tangent plane; twice that, then eight times.
  const double delta = rho0 - std::sqrt(std::max(rho0 * rho0 - x.squaredNorm(), 0.0));
  bool found = false;
  for (double f : kProjectionBrackets) {
    Index cell = cell_[v];
    if (skin_.project_along_line(q, n0, f * delta * (1 + kProjectionSlack) + kProjectionSlackL * L_, t.p, cell)) {
      t.s = skin_.sample(t.p, cell);
      found = true;
      break;
    }
  }
  if (!found || (t.p - p0).norm() > max_offset) return t;
  const std::size_t k = ring.size();
  for (std::size_t i = 0; i < k; ++i) {
    const Vec3 &a = pos(ring[i]), &b = pos(ring[(i + 1) % k]);
    if (!((a - t.p).cross(b - t.p).dot(n0) > 0)) return t;  // folded over in the tangent plane
  }
  for (std::size_t i = 0; i < k; ++i)
    if (!skin::satisfies_L(t.p, pos(ring[i]), t.s.rho, rho_[ring[i]], size_)) {
      if (why) *why = Refusal::L;
      return t;
    }
  double qmin = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < k; ++i) {
    const Vertex a = ring[i], b = ring[(i + 1) % k];
    if (!skin::satisfies_U(t.p, pos(a), pos(b), t.s.rho, rho_[a], rho_[b], size_)) {
      if (why) *why = Refusal::U;
      return t;
    }
    qmin = std::min(qmin, min_angle(t.p, pos(a), pos(b)));
  }
  t.q = qmin;
  return t;
}

bool AngleImprover::in_ball(FaceGeometry& g, const Vec3& x) const {
  const Vec3 &a = pos(Vertex(g.v[0])), &b = pos(Vertex(g.v[1])), &c = pos(Vertex(g.v[2]));
  if (skin::outside_every_surface_ball(a, b, c, x, L_)) return false;
  if (g.ball == FaceGeometry::Ball::NotComputed) {
    Index cell = cell_[Vertex(g.v[0])];
    if (skin::surface_delaunay_centre(skin_, a, b, c, g.m, cell)) {
      g.ball = FaceGeometry::Ball::Valid;
      g.r = std::max({(g.m - a).norm(), (g.m - b).norm(), (g.m - c).norm()});
    } else {
      g.ball = FaceGeometry::Ball::None;
    }
  }
  if (g.ball == FaceGeometry::Ball::None)
    return true;  // already a violation for the verifier: leave its surroundings alone
  return (x - g.m).norm() < g.r * (1 + opt_.ball_margin);
}

Refusal AngleImprover::admissible(Vertex v, const Trial& t, const std::vector<Vertex>& ring,
                                  const std::vector<Vertex>& nearby, std::vector<FaceGeometry>& faces) {
  const Vec3& p = t.p;
  const Vec3 np = t.s.gradient.normalized();
  const std::size_t k = ring.size();
  // 1. Every star triangle faces along the skin normals of its corners.
  for (std::size_t i = 0; i < k; ++i) {
    const Vertex a = ring[i], b = ring[(i + 1) % k];
    const Vec3 nt = (pos(a) - p).cross(pos(b) - p);
    if (!(nt.dot(np) > 0 && nt.dot(normal_[a]) > 0 && nt.dot(normal_[b]) > 0)) return Refusal::Orientation;
  }
  // 2. Restricted Delaunay: the star triangles' surface balls exist and
  //    hold no other vertex; p lies in no other triangle's surface ball.
  for (std::size_t i = 0; i < k; ++i) {
    const Vertex a = ring[i], b = ring[(i + 1) % k];
    Vec3 m;
    Index cell = t.s.cell;
    if (!skin::surface_delaunay_centre(skin_, p, pos(a), pos(b), m, cell)) return Refusal::Rdt;
    const double r = std::max({(m - p).norm(), (m - pos(a)).norm(), (m - pos(b)).norm()}) * (1 + opt_.ball_margin);
    for (Vertex x : nearby)
      if (x != a && x != b && (pos(x) - m).squaredNorm() < r * r) return Refusal::Rdt;
  }
  for (FaceGeometry& g : faces) {
    // The ball's centre is within 2R of cc and its radius at most sqrt5 R.
    if ((p - g.cc).norm() > (2 + kSqrt5) * g.R * (1 + kBoundPad) + kBoundPadL * L_) continue;
    if (in_ball(g, p)) return Refusal::Rdt;
  }
  // 3. No star triangle meets another triangle (exact predicates; the
  //    circumballs, which hold the triangles, filter the pairs). v is put at
  //    p for the test and put back.
  const Vec3 p0 = pos(v);
  mesh_.position(v) = p;
  const auto& P = mesh_.positions().vector();
  Refusal verdict = Refusal::None;
  std::vector<std::array<Index, 3>> star(k);
  std::vector<Vec3> scc(k);
  std::vector<double> sR(k);
  for (std::size_t i = 0; i < k; ++i) {
    const Vertex a = ring[i], b = ring[(i + 1) % k];
    star[i] = {v.idx(), a.idx(), b.idx()};
    scc[i] = skin::circumcentre(p, pos(a), pos(b));
    sR[i] = std::max({(scc[i] - p).norm(), (scc[i] - pos(a)).norm(), (scc[i] - pos(b)).norm()});
  }
  for (std::size_t i = 0; i < k && verdict == Refusal::None; ++i) {
    for (std::size_t j = i + 1; j < k && verdict == Refusal::None; ++j)
      if (geometry::mesh_triangles_intersect(star[i], star[j], P)) verdict = Refusal::Intersection;
    for (const FaceGeometry& g : faces) {
      if (verdict != Refusal::None) break;
      if ((g.cc - scc[i]).norm() > (g.R + sR[i]) * (1 + kBoundPad) + kBoundPadL * L_) continue;
      if (geometry::mesh_triangles_intersect(star[i], g.v, P)) verdict = Refusal::Intersection;
    }
  }
  mesh_.position(v) = p0;
  return verdict;
}

void AngleImprover::build_static_grid(const std::vector<std::pair<double, Vertex>>& cands) {
  // A candidate c is tried once per pass, where it is now. Its query then
  // reaches reach({c, M, S}) with M and S from its ring at that moment; a
  // ring vertex u that moved before it in the pass moved at most 2 M_u
  // (every trial lies within twice the tangent move, `relevant`), and M_u <=
  // max_move_factor |u - c|: so every ring distance, and with it M and S,
  // grows by at most gamma = 1 + 2 max_move_factor, and reach, whose terms
  // grow at most linearly with M and S, by at most gamma too.
  const double gamma = 1 + 2 * opt_.max_move_factor;
  covered_.clear();
  std::vector<Vertex> ring;
  std::vector<Vec3> centre;
  std::vector<double> radius;
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const auto& [q, c] : cands) {
    ring_of(c, ring);  // true: the pass keeps only vertices with a ring
    double shortest = std::numeric_limits<double>::infinity(), S = 0;
    for (Vertex u : ring) {
      const double d = (pos(u) - pos(c)).norm();
      shortest = std::min(shortest, d), S = std::max(S, d);
    }
    const double R = gamma * reach({c, opt_.max_move_factor * shortest, S}) * (1 + kBoundPad);
    covered_.emplace(c.idx(), R);
    centre.push_back(pos(c));
    radius.push_back(R);
    lo = lo.cwiseMin(pos(c) - Vec3::Constant(R)), hi = hi.cwiseMax(pos(c) + Vec3::Constant(R));
  }
  // A bitmap of cubic cells over the balls' box, side the median radius, or
  // more to stay within kMaxCoverCells and kMarksPerCandidate: the cells
  // each ball's box meets. Larger cells only keep more vertices.
  std::vector<double> sorted = radius;
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
  double h = std::max(sorted[sorted.size() / 2], kMinScale);
  const Vec3 extent = hi - lo;
  auto cells = [&](double side) {
    return (std::floor(extent.x() / side) + 1) * (std::floor(extent.y() / side) + 1) *
           (std::floor(extent.z() / side) + 1);
  };
  auto marks = [&](double side) {
    double m = 0;
    for (double R : radius) m += std::pow(std::min(2 * R / side + 2, std::floor(extent.maxCoeff() / side) + 1), 3);
    return m;
  };
  while (cells(h) > kMaxCoverCells || marks(h) > kMarksPerCandidate * double(radius.size())) h *= 2;
  std::array<std::int64_t, 3> n{};
  for (int k = 0; k < 3; ++k) n[k] = static_cast<std::int64_t>(std::floor(extent[k] / h)) + 1;
  auto cell_of = [&](double x, int k) { return static_cast<std::int64_t>(std::floor((x - lo[k]) / h)); };
  std::vector<std::uint64_t> bits(static_cast<std::size_t>((n[0] * n[1] * n[2] + 63) / 64), 0);
  for (std::size_t i = 0; i < centre.size(); ++i) {
    std::array<std::int64_t, 3> a{}, b{};
    for (int k = 0; k < 3; ++k) {
      a[k] = std::clamp<std::int64_t>(cell_of(centre[i][k] - radius[i], k), 0, n[k] - 1);
      b[k] = std::clamp<std::int64_t>(cell_of(centre[i][k] + radius[i], k), 0, n[k] - 1);
    }
    for (std::int64_t x = a[0]; x <= b[0]; ++x)
      for (std::int64_t y = a[1]; y <= b[1]; ++y)
        for (std::int64_t z = a[2]; z <= b[2]; ++z) {
          const auto bit = static_cast<std::uint64_t>((x * n[1] + y) * n[2] + z);
          bits[bit >> 6] |= std::uint64_t{1} << (bit & 63);
        }
  }
  // A vertex within R of a centre has each coordinate within R of it, and
  // the cell index is monotone in the coordinate: its cell is marked. The
  // vertices are read in blocks on the threads and inserted in index order.
  const std::size_t nv = mesh_.vertices_size(), blocks = (nv + kScanGrain - 1) / kScanGrain;
  std::vector<std::vector<Index>> kept(blocks);
  parallel_for(blocks, threads_, 1, [&](std::size_t k) {
    for (std::size_t i = k * kScanGrain, end = std::min(nv, i + kScanGrain); i < end; ++i) {
      const Vertex x(static_cast<Index>(i));
      if (mesh_.is_deleted(x) || moved_[i]) continue;
      const Vec3& p = pos(x);
      std::array<std::int64_t, 3> c{};
      bool inside = true;
      for (int a = 0; a < 3; ++a) {
        c[a] = cell_of(p[a], a);
        inside = inside && c[a] >= 0 && c[a] < n[a];
      }
      if (!inside) continue;
      const auto bit = static_cast<std::uint64_t>((c[0] * n[1] + c[1]) * n[2] + c[2]);
      if (bits[bit >> 6] >> (bit & 63) & 1) kept[k].push_back(x.idx());
    }
  });
  grid_.emplace(cell_per_scale_, kGridOctaves, /*erasable=*/false);
  for (const std::vector<Index>& list : kept)
    for (Index i : list) grid_->insert(i, pos(Vertex(i)), rho_[Vertex(i)]);
}

bool AngleImprover::try_improve(Vertex v) {
  std::vector<Vertex> ring;
  if (!ring_of(v, ring)) return false;
  const std::size_t k = ring.size();
  const Vec3 p0 = pos(v);
  const double q0 = star_min(p0, ring);
  if (!(q0 < opt_.target_angle_deg * kDegree)) return false;
  double shortest = std::numeric_limits<double>::infinity(), S = 0;
  for (Vertex u : ring) {
    const double d = (pos(u) - p0).norm();
    shortest = std::min(shortest, d);
    S = std::max(S, d);
  }
  const double M = opt_.max_move_factor * shortest;
  ++stats_.attempts;

  // The ascent (after Freitag, Jones & Plassmann 1995): along the min-norm
  // element of the convex hull of the active angles' gradients in the
  // tangent plane at p0, a step predicted from the linearisation, halved
  // until the star's minimum angle (exact, at the projected point, with
  // [L] and [U] kept) increases.
  const Vec3 n0 = normal_[v];
  const Vec3 t1 = n0.unitOrthogonal(), t2 = n0.cross(t1);
  const double max_offset = 2 * M;
  std::vector<Trial> path;
  Trial cur;
  cur.p = p0;
  cur.q = q0;
  std::vector<double> theta(3 * k);
  std::vector<Vec2> grad(3 * k);
  std::vector<Vec2> active;
  Refusal ascent_why = Refusal::None;
  for (int step = 0; step < opt_.max_ascent_steps; ++step) {
    // Angles of the star at cur.p and their gradients with respect to the
    // position of v, on (t1, t2).
    const Vec3& p = cur.p;
    for (std::size_t i = 0; i < k; ++i) {
      const Vec3 &a = pos(ring[i]), &b = pos(ring[(i + 1) % k]);
      const Vec3 ea = a - p, eb = b - p;
      const double la = ea.norm(), lb = eb.norm();
      const Vec3 ua = ea / la, ub = eb / lb;
      // Angle at v: d/dp = w_a / |ea| + w_b / |eb|, w_a the unit vector
      // along eb's component orthogonal to ea (and vice versa).
      const Vec3 gv = (ub - ub.dot(ua) * ua).normalized() / la + (ua - ua.dot(ub) * ub).normalized() / lb;
      // Angle at a (between p - a and b - a): d/dp = -w / |p - a|, w the
      // unit vector along (b - a)'s component orthogonal to p - a.
      const Vec3 ba = b - a, ab = a - b;
      const Vec3 wa = (ba - ba.dot(-ua) * -ua).normalized(), wb = (ab - ab.dot(-ub) * -ub).normalized();
      theta[3 * i] = geometry::corner_angle(p, a, b);
      theta[3 * i + 1] = geometry::corner_angle(a, b, p);
      theta[3 * i + 2] = geometry::corner_angle(b, p, a);
      grad[3 * i] = Vec2(gv.dot(t1), gv.dot(t2));
      grad[3 * i + 1] = -Vec2(wa.dot(t1), wa.dot(t2)) / la;
      grad[3 * i + 2] = -Vec2(wb.dot(t1), wb.dot(t2)) / lb;
    }
    const double tmin = *std::min_element(theta.begin(), theta.end());
    active.clear();
    for (std::size_t i = 0; i < theta.size(); ++i)
      if (theta[i] <= tmin + kActiveBand && grad[i].allFinite()) active.push_back(grad[i]);
    if (active.empty()) break;
    // Min-norm element of conv(active): a vertex or a point of a segment
    // that every active gradient sees at least as far (d·g >= |d|²); none
    // if the origin is inside (a local maximum of the minimum angle).
    Vec2 d = Vec2::Zero();
    double best = std::numeric_limits<double>::infinity();
    auto consider = [&](const Vec2& cand) {
      const double n2 = cand.squaredNorm();
      if (!(n2 < best)) return;
      for (const Vec2& g : active)
        if (cand.dot(g) < n2 * (1 - 1e-9)) return;
      best = n2, d = cand;
    };
    for (std::size_t i = 0; i < active.size(); ++i) {
      consider(active[i]);
      for (std::size_t j = i + 1; j < active.size(); ++j) {
        const Vec2 e = active[j] - active[i];
        const double ee = e.squaredNorm();
        if (ee > 0) consider(active[i] + std::clamp(-active[i].dot(e) / ee, 0.0, 1.0) * e);
      }
    }
    if (!(best < std::numeric_limits<double>::infinity()) || !(d.norm() > 1e-12 * active[0].norm())) break;
    const Vec2 dir = d.normalized();
    // Predicted step: until an inactive angle that rises more slowly meets
    // the active minimum (rates along dir), within the move bound M.
    double rate = std::numeric_limits<double>::infinity();
    for (const Vec2& g : active) rate = std::min(rate, g.dot(dir));
    double s = max_offset;
    for (std::size_t i = 0; i < theta.size(); ++i) {
      if (theta[i] <= tmin + kActiveBand) continue;
      const double ri = grad[i].dot(dir);
      if (ri < rate) s = std::min(s, (theta[i] - tmin) / (rate - ri));
    }
    const double bx = cur.x.dot(dir), c2 = cur.x.squaredNorm() - M * M;
    s = std::min(s, -bx + std::sqrt(std::max(bx * bx - c2, 0.0)));
    bool improved = false;
    for (int h = 0; h <= kMaxHalvings && s > 1e-9 * shortest; ++h, s *= 0.5) {
      Refusal why = Refusal::None;
      Trial t = evaluate(cur.x + s * dir, v, n0, t1, t2, max_offset, ring, &why);
      if (t.q > cur.q) {
        cur = t;
        path.push_back(std::move(t));
        improved = true;
        break;
      }
      if (why != Refusal::None) ascent_why = why;
    }
    if (!improved) break;
  }
  // Two more candidates: the centroid of the ring in the tangent plane
  // (Laplacian smoothing) and half the ascent's best move.
  {
    Vec3 centroid = Vec3::Zero();
    for (Vertex u : ring) centroid += pos(u);
    centroid /= double(k);
    Vec2 x((centroid - p0).dot(t1), (centroid - p0).dot(t2));
    if (x.norm() > M) x *= M / x.norm();
    Trial t = evaluate(x, v, n0, t1, t2, max_offset, ring, nullptr);
    if (t.q > q0) path.push_back(std::move(t));
    if (!path.empty()) {
      t = evaluate(0.5 * cur.x, v, n0, t1, t2, max_offset, ring, nullptr);
      if (t.q > q0) path.push_back(std::move(t));
    }
  }
  if (path.empty()) {
    if (ascent_why == Refusal::L) ++stats_.refused_L;
    if (ascent_why == Refusal::U) ++stats_.refused_U;
    return false;
  }
  // Best first (stable: ties keep the ascent's order).
  std::stable_sort(path.begin(), path.end(), [](const Trial& a, const Trial& b) { return a.q > b.q; });

  // The neighbourhood: the relevant vertices (marked), and the triangles
  // with three marked corners, without the star (no other triangle can
  // matter: "Which triangles a move can affect").
  // The marks are sets of the neighbourhood's size, not arrays over the mesh.
  const std::vector<Vertex> nearby = neighbourhood({v, M, S});
  std::vector<Index> marked(nearby.size());
  for (std::size_t i = 0; i < nearby.size(); ++i) marked[i] = nearby[i].idx();
  std::sort(marked.begin(), marked.end());
  std::unordered_set<Index> listed;
  listed.reserve(4 * nearby.size());
  std::vector<FaceGeometry> faces;
  for (Vertex x : nearby)
    for (Face f : mesh_.faces(x)) {
      if (!listed.insert(f.idx()).second) continue;
      FaceGeometry g;
      int i = 0;
      bool keep = true;
      for (Vertex y : mesh_.vertices(f))
        keep = keep && std::binary_search(marked.begin(), marked.end(), y.idx()), g.v[i++] = y.idx();
      if (!keep) continue;  // a star triangle (v is not marked) or one that cannot matter
      const Vec3 &a = pos(Vertex(g.v[0])), &b = pos(Vertex(g.v[1])), &cc = pos(Vertex(g.v[2]));
      g.cc = skin::circumcentre(a, b, cc);
      g.R = std::max({(g.cc - a).norm(), (g.cc - b).norm(), (g.cc - cc).norm()});
      faces.push_back(g);
    }

  // The best positions first; then, if all of them are refused, shorter
  // moves along the best one (a move that makes a neighbour's edge
  // non-Delaunay is refused however short, but one that only reaches a
  // farther ball is not).
  if (path.size() > std::size_t(kMaxChecked)) path.resize(kMaxChecked);
  const Vec2 best_x = path.front().x;
  const std::size_t n_best = path.size();
  Trial shorter;
  for (std::size_t i = 0; i < n_best + kShorterMoves; ++i) {
    if (i >= n_best) {
      const double f = std::ldexp(1.0, -2 - int(i - n_best));  // 1/4, 1/8, 1/16
      shorter = evaluate(f * best_x, v, n0, t1, t2, max_offset, ring, nullptr);
      if (!(shorter.q > q0)) continue;
    }
    const Trial& t = i < n_best ? path[i] : shorter;
    const Refusal why = admissible(v, t, ring, nearby, faces);
    if (why == Refusal::None) {
      mesh_.position(v) = t.p;
      cell_[v] = t.s.cell;          // and with it t.s's normal and rho
      moved_grid_->erase(v.idx());  // moved before: its entry is at its last position
      moved_grid_->insert(v.idx(), t.p, rho_[v]);
      moved_[v.idx()] = 1;
      for (Face f : mesh_.faces(v)) touched_.push_back(f);
      ++stats_.moves;
      return true;
    }
    switch (why) {
      case Refusal::Orientation:
        ++stats_.refused_orientation;
        break;
      case Refusal::Rdt:
        ++stats_.refused_rdt;
        break;
      default:
        ++stats_.refused_intersection;
        break;
    }
  }
  ++stats_.refused;
  return false;
}

AngleImprovementStats AngleImprover::run() {
  // Faces below the target at the start: with the moved stars, the only
  // ones whose smallest angle can be below the target at the end.
  std::vector<Face> low_faces;
  Face worst_high;
  double kappa0 = 0;
  stats_.min_angle_before_deg = scan(&low_faces, &kappa0, &worst_high);
  stats_.low_triangles = low_faces.size();
  stats_.min_angle_after_deg = stats_.min_angle_before_deg;
  kappa_ = std::max(kappa0, size_.C * size_.Q);
  stats_.kappa = kappa_;
  if (kappa_ > kMaxKappa) {
    stats_.skipped = true;
    return stats_;
  }
  const double target = opt_.target_angle_deg * kDegree;
  std::vector<Vertex> low;
  for (Face f : low_faces)
    for (Vertex x : mesh_.vertices(f)) low.push_back(x);
  std::sort(low.begin(), low.end());
  low.erase(std::unique(low.begin(), low.end()), low.end());
  std::vector<Vertex> todo = std::move(low);
  std::vector<Vertex> ring;
  for (int pass = 0; pass < opt_.max_passes && !todo.empty(); ++pass) {
    // This pass's candidates, worst star first (ties: vertex index).
    std::vector<std::pair<double, Vertex>> cands;
    for (Vertex v : todo) {
      if (!ring_of(v, ring)) continue;
      const double q = star_min(pos(v), ring);
      if (q < target) cands.push_back({q, v});
    }
    if (cands.empty()) break;
    ++stats_.passes;
    std::sort(cands.begin(), cands.end());
    if (!moved_grid_) {
      // Cells of half the median reach over rho of the first candidates,
      // times the scale of each level.
      std::vector<double> r;
      for (const auto& [q, v] : cands) {
        ring_of(v, ring);
        double shortest = std::numeric_limits<double>::infinity(), S = 0;
        for (Vertex u : ring) {
          const double d = (pos(u) - pos(v)).norm();
          shortest = std::min(shortest, d), S = std::max(S, d);
        }
        r.push_back(reach({v, opt_.max_move_factor * shortest, S}) / std::max(rho_[v], kMinScale));
      }
      std::nth_element(r.begin(), r.begin() + r.size() / 2, r.end());
      cell_per_scale_ = 0.5 * r[r.size() / 2];
      moved_grid_.emplace(cell_per_scale_, kGridOctaves);
      moved_.assign(mesh_.vertices_size(), 0);
    }
    build_static_grid(cands);
    std::vector<Vertex> next;
    for (const auto& [q, v] : cands) {
      if (!try_improve(v)) continue;
      next.push_back(v);
      for (Vertex u : mesh_.vertices(v)) next.push_back(u);
    }
    std::sort(next.begin(), next.end());
    next.erase(std::unique(next.begin(), next.end()), next.end());
    todo = std::move(next);
  }
  if (stats_.moves > 0) {
    // Faces neither below the target at the start nor in a moved star kept
    // their angles, the smallest of which is worst_high's unless a move
    // touched it (then scan everything again).
    double q = std::numeric_limits<double>::infinity();
    for (const std::vector<Face>* list : {&low_faces, &touched_})
      for (Face f : *list) q = std::min(q, face_min_angle(f));
    const bool high_touched = std::find(touched_.begin(), touched_.end(), worst_high) != touched_.end();
    if (high_touched) {
      Face unused;
      stats_.min_angle_after_deg = scan(nullptr, nullptr, &unused);
    } else {
      if (worst_high.is_valid()) q = std::min(q, face_min_angle(worst_high));
      stats_.min_angle_after_deg = q / kDegree;
    }
  }
  return stats_;
}

}  // namespace

AngleImprovementStats improve_angles(const skin::SkinSurface& skin, SurfaceMesh& mesh,
                                     const AngleImprovementOptions& opt, const skin::RunContext& run) {
  AngleImprover a(skin, mesh, opt, run.size, thread_count(run.threads));
  return a.run();
}

}  // namespace skinmesh::refine

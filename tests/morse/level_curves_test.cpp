// tests/morse/level_curves_test.cpp: the level curves of the height function
// (the decomposed sweep's cut curves, papers/morse/level_curves.md) against
// circles of spheres and against a brute-force count of the curves from the
// skin function sampled on a fine grid of the cutting plane.
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/stage_clock.h"
#include "dynamic/dynamic_skin.h"
#include "morse/level_curves.h"
#include "morse/morse_smale_complex.h"
#include "skin/molecule_io.h"
#include "skin/skin_surface.h"
#include "tests/skin/skin_test_util.h"

using namespace skinmesh;

namespace {

/// The number of closed curves of F ∩ {e·x = c} by brute force: the body's
/// section {f < 0} sampled at the centres of a square grid of spacing g on
/// the plane (padded so that the border is outside); its boundary curves are
/// the section's components (4-connected) plus its holes (components of the
/// outside, 8-connected, that do not reach the border).
int brute_force_curve_count(const skin::SkinSurface& skin, const Vec3& e, double c, double g) {
  Vec3 u = e.unitOrthogonal(), v = e.cross(u);
  double lo_u = 1e300, hi_u = -1e300, lo_v = 1e300, hi_v = -1e300;
  for (const auto& p : skin.points()) {
    const double r = std::sqrt(std::max(p.w, 0.0));
    lo_u = std::min(lo_u, p.z.dot(u) - r), hi_u = std::max(hi_u, p.z.dot(u) + r);
    lo_v = std::min(lo_v, p.z.dot(v) - r), hi_v = std::max(hi_v, p.z.dot(v) + r);
  }
  lo_u -= 2 * g, lo_v -= 2 * g, hi_u += 2 * g, hi_v += 2 * g;
  const int nu = static_cast<int>(std::ceil((hi_u - lo_u) / g)), nv = static_cast<int>(std::ceil((hi_v - lo_v) / g));
  std::vector<char> inside(static_cast<std::size_t>(nu) * nv);
  Index hint = kInvalidIndex;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int ii = j % 2 ? nu - 1 - i : i;  // serpentine, so that the hint stays close
      const Vec3 q = (lo_u + (ii + 0.5) * g) * u + (lo_v + (j + 0.5) * g) * v + c * e;
      const auto s = skin.sample(q, hint);
      hint = s.cell;
      inside[static_cast<std::size_t>(j) * nu + ii] = s.f < 0;
    }
  std::vector<int> label(inside.size(), -1);
  auto flood = [&](int start, bool in, bool eight, bool& border) {
    std::vector<int> stack{start};
    label[start] = 1;
    border = false;
    while (!stack.empty()) {
      const int k = stack.back();
      stack.pop_back();
      const int i = k % nu, j = k / nu;
      if (i == 0 || j == 0 || i == nu - 1 || j == nv - 1) border = true;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          if ((di == 0 && dj == 0) || (!eight && di != 0 && dj != 0)) continue;
          const int a = i + di, b = j + dj;
          if (a < 0 || b < 0 || a >= nu || b >= nv) continue;
          const int kk = b * nu + a;
          if (label[kk] < 0 && static_cast<bool>(inside[kk]) == in) label[kk] = 1, stack.push_back(kk);
        }
    }
  };
  int count = 0;
  for (int k = 0; k < nu * nv; ++k) {
    if (label[k] >= 0) continue;
    bool border = false;
    const bool in = inside[k];
    flood(k, in, /*eight=*/!in, border);
    if (in || !border) ++count;
  }
  return count;
}

/// Every property a cut curve must have: samples on the skin and on the
/// plane, edges within the sampling window, oriented by n × e, and no two
/// curves (or two non-adjacent edges of one) closer than their spacing.
void check_curves(const skin::SkinSurface& skin, const Vec3& e, double c, const std::vector<morse::LevelCurve>& curves,
                  const morse::LevelCurveOptions& opt) {
  const double tol = 1e-9 * skin.length_scale();
  for (const auto& curve : curves) {
    const std::size_t n = curve.points.size();
    REQUIRE(n >= 3);
    REQUIRE(curve.rho.size() == n);
    REQUIRE(curve.cells.size() == n);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& p = curve.points[i];
      const Vec3& q = curve.points[(i + 1) % n];
      const auto s = skin.sample(p, curve.cells[i]);
      CHECK(std::abs(s.f) / s.gradient.norm() < tol);
      CHECK(std::abs(e.dot(p) - c) < tol);
      CHECK(s.rho == doctest::Approx(curve.rho[i]).epsilon(1e-12));
      // The spacing in the metric of rho: about the target at most (the
      // sampler integrates 1 / rho along the fine polyline, this reads rho at
      // the two ends only: a few per cent apart where rho bends between
      // cells), at least three quarters of it.
      const double ratio = (q - p).norm() / (opt.spacing * 0.5 * (curve.rho[i] + curve.rho[(i + 1) % n]));
      CHECK(ratio <= 1.05);
      CHECK(ratio >= 0.7);
      // Oriented: the edge runs along n × e.
      CHECK((q - p).dot(s.gradient.normalized().cross(e)) > 0);
    }
  }
  // Distinct curves, and distinct parts of one curve, stay apart: a curve
  // traced twice, or two curves merged, would bring samples together.
  for (std::size_t a = 0; a < curves.size(); ++a)
    for (std::size_t b = a; b < curves.size(); ++b) {
      const auto& A = curves[a];
      const auto& B = curves[b];
      for (std::size_t i = 0; i < A.points.size(); ++i)
        for (std::size_t j = a == b ? i + 1 : 0; j < B.points.size(); ++j) {
          const std::size_t n = A.points.size();
          if (a == b && (j - i <= 2 || n - (j - i) <= 2)) continue;
          CHECK((A.points[i] - B.points[j]).norm() > 0.25 * opt.spacing * std::min(A.rho[i], B.rho[j]));
        }
    }
}

/// True if x lies in the part of the skin below the cut with detours:
/// ({h <= c} minus the unions of balls that go up) plus those that go down.
bool below_cut(const Vec3& x, const Vec3& e, double c, const std::vector<morse::CutDetour>& detours) {
  for (const auto& d : detours)
    for (const auto& b : d.balls)
      if ((x - b.center).norm() < b.radius) return !d.upper;
  return e.dot(x) <= c;
}

/// A fine mesh of the skin for the brute-force count: a mesh subdivided
/// `levels` times (midpoints pulled back onto the skin), with its edges
/// numbered.
struct FineMesh {
  std::vector<Vec3> positions;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<std::array<Index, 3>> triangle_edges;  ///< edge k joins corners k and k + 1
  std::vector<std::pair<Index, Index>> edges;
};

/// The edges of `triangles` as sorted keys (smaller index in the high word),
/// and each triangle's three edges as indices into them.
std::vector<std::uint64_t> number_edges(const std::vector<std::array<Index, 3>>& triangles,
                                        std::vector<std::array<Index, 3>>& triangle_edges) {
  auto key = [](Index a, Index b) { return std::uint64_t(std::min(a, b)) << 32 | std::max(a, b); };
  std::vector<std::uint64_t> keys;
  keys.reserve(3 * triangles.size());
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) keys.push_back(key(t[k], t[(k + 1) % 3]));
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  triangle_edges.resize(triangles.size());
  for (std::size_t i = 0; i < triangles.size(); ++i)
    for (int k = 0; k < 3; ++k)
      triangle_edges[i][k] = static_cast<Index>(
          std::lower_bound(keys.begin(), keys.end(), key(triangles[i][k], triangles[i][(k + 1) % 3])) - keys.begin());
  return keys;
}

FineMesh fine_mesh(const skin::SkinSurface& skin, const geometry::IndexedMesh& m, int levels) {
  FineMesh f;
  f.positions = m.positions;
  f.triangles = m.triangles;
  for (int l = 0; l < levels; ++l) {
    std::vector<std::array<Index, 3>> te;
    const std::vector<std::uint64_t> keys = number_edges(f.triangles, te);
    const Index first = static_cast<Index>(f.positions.size());
    for (std::uint64_t k : keys) {
      Index cell = kInvalidIndex;
      f.positions.push_back(skin.pull_back(0.5 * (f.positions[k >> 32] + f.positions[k & 0xffffffffu]), cell));
    }
    std::vector<std::array<Index, 3>> next;
    next.reserve(4 * f.triangles.size());
    for (std::size_t i = 0; i < f.triangles.size(); ++i) {
      const auto& t = f.triangles[i];
      const Index ab = first + te[i][0], bc = first + te[i][1], ca = first + te[i][2];
      next.push_back({t[0], ab, ca}), next.push_back({ab, t[1], bc});
      next.push_back({ca, bc, t[2]}), next.push_back({ab, bc, ca});
    }
    f.triangles = std::move(next);
  }
  for (std::uint64_t k : number_edges(f.triangles, f.triangle_edges))
    f.edges.emplace_back(static_cast<Index>(k >> 32), static_cast<Index>(k & 0xffffffffu));
  return f;
}

/// The number of closed curves bounding the part of the skin below a cut
/// with detours, by brute force: the triangles of a fine mesh whose three
/// vertices lie below the cut, and the connected components of their
/// boundary edges.
int brute_force_cut_count(const FineMesh& m, const Vec3& e, double c, const std::vector<morse::CutDetour>& detours) {
  std::vector<char> in(m.positions.size());
  for (std::size_t v = 0; v < in.size(); ++v) in[v] = below_cut(m.positions[v], e, c, detours);
  std::vector<int> edge_count(m.edges.size(), 0);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    if (!in[tri[0]] || !in[tri[1]] || !in[tri[2]]) continue;
    for (int k = 0; k < 3; ++k) ++edge_count[m.triangle_edges[t][k]];
  }
  std::vector<Index> parent(m.positions.size());
  std::iota(parent.begin(), parent.end(), Index(0));
  std::function<Index(Index)> find = [&](Index a) { return parent[a] == a ? a : parent[a] = find(parent[a]); };
  std::vector<char> on_boundary(m.positions.size(), 0);
  for (std::size_t k = 0; k < m.edges.size(); ++k) {
    if (edge_count[k] != 1) continue;
    const auto [a, b] = m.edges[k];
    on_boundary[a] = on_boundary[b] = 1;
    parent[find(a)] = find(b);
  }
  int count = 0;
  for (std::size_t v = 0; v < parent.size(); ++v)
    if (on_boundary[v] && find(static_cast<Index>(v)) == static_cast<Index>(v)) ++count;
  return count;
}

/// Every property a cut with detours must have: samples on the skin; an edge
/// on the level set has both ends on the plane and outside every ball and
/// runs along n × e; an edge on a ball's circle has both ends on its sphere
/// and outside the cluster's other balls, lies on the cut's side of the
/// plane, and runs with the ball on its right if the cluster goes up (left if
/// it goes down). Counts the edges on circles and the corners (where the cut
/// turns from one ball's circle to another's).
void check_detoured(const skin::SkinSurface& skin, const Vec3& e, double c,
                    const std::vector<morse::CutDetour>& detours, const std::vector<morse::LevelCurve>& curves,
                    int& detoured_edges, int& corners) {
  const double tol = 1e-9 * skin.length_scale();
  for (const auto& curve : curves) {
    const std::size_t n = curve.points.size();
    REQUIRE(n >= 3);
    REQUIRE(curve.detour.size() == n);
    REQUIRE(curve.ball.size() == n);
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3& p = curve.points[i];
      const Vec3& q = curve.points[(i + 1) % n];
      const auto s = skin.sample(p, curve.cells[i]);
      CHECK(std::abs(s.f) / s.gradient.norm() < tol);
      const Index d = curve.detour[i];
      if (d == kInvalidIndex) {
        CHECK(curve.ball[i] == kInvalidIndex);
        CHECK(std::abs(e.dot(p) - c) < tol);
        CHECK(std::abs(e.dot(q) - c) < tol);
        for (const auto& cluster : detours)
          for (const auto& b : cluster.balls) CHECK((p - b.center).norm() > b.radius - tol);
        CHECK((q - p).dot(s.gradient.normalized().cross(e)) > 0);
        continue;
      }
      REQUIRE(d < detours.size());
      REQUIRE(curve.ball[i] < detours[d].balls.size());
      ++detoured_edges;
      const std::size_t prev = (i + n - 1) % n;
      if (curve.detour[prev] == d && curve.ball[prev] != curve.ball[i]) ++corners;
      const auto& cluster = detours[d];
      const auto& b = cluster.balls[curve.ball[i]];
      CHECK(std::abs((p - b.center).norm() - b.radius) < tol);
      CHECK(std::abs((q - b.center).norm() - b.radius) < tol);
      for (std::size_t k = 0; k < cluster.balls.size(); ++k)
        if (k != curve.ball[i]) CHECK((p - cluster.balls[k].center).norm() > cluster.balls[k].radius - tol);
      CHECK((cluster.upper ? e.dot(p) - c : c - e.dot(p)) < tol);
      const Vec3 u = (p - b.center).normalized();
      CHECK((q - p).dot((cluster.upper ? -1.0 : 1.0) * s.gradient.normalized().cross(u)) > 0);
    }
  }
}
}  // namespace

TEST_SUITE("morse") {

TEST_CASE("level curves of one ball: the circle at every height, traced from the only minimum") {
  const double R = 1.7;
  const Vec3 centre(0.3, -0.2, 0.1);
  const skin::SkinSurface skin({{centre, 2 * R * R}});
  std::mt19937 rng(5);
  for (int k = 0; k < 5; ++k) {
    const Vec3 e = test::random_rotation(rng).col(0);
    const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, e);
    REQUIRE(ms.critical.size() == 2);  // no saddle: the seed comes from the ascent
    for (double t : {-0.9, -0.4, 0.0, 0.55, 0.85}) {
      const double c = e.dot(centre) + t * R;
      CAPTURE(c);
      const auto curves = morse::level_curves(skin, ms, c);
      REQUIRE(curves.size() == 1);
      const double radius = R * std::sqrt(1 - t * t);
      CHECK(curves[0].length == doctest::Approx(2 * kPi * radius).epsilon(1e-3));
      for (const Vec3& p : curves[0].points) CHECK((p - (centre + t * R * e)).norm() == doctest::Approx(radius));
      // Samples at 0.185 rho = 0.185 R: ceil of the circle's length over that.
      CHECK(curves[0].points.size() == static_cast<std::size_t>(std::ceil(2 * kPi * radius / (0.185 * R) - 1e-9)));
      check_curves(skin, e, c, curves, {});
    }
    // Above the maximum and below the minimum: no curve.
    CHECK(morse::level_curves(skin, ms, e.dot(centre) + 1.01 * R).empty());
    CHECK(morse::level_curves(skin, ms, e.dot(centre) - 1.01 * R).empty());
  }
}

TEST_CASE("level curves of four balls apart: one curve each, every seed from an ascent") {
  std::mt19937 rng(7);
  for (int k = 0; k < 3; ++k) {
    const Vec3 e = test::random_rotation(rng).col(1);
    const Vec3 u = e.unitOrthogonal(), v = e.cross(u);
    // Centres in the plane normal to e, 3 Å apart at least: weighted balls of
    // radius sqrt(2) do not meet, so the skin is four unit spheres.
    const std::vector<geometry::WeightedPoint> balls{
        {3 * u, 2.0}, {-3 * u, 2.0}, {3 * v, 2.0}, {-3 * v + 0.25 * e, 2.0}};
    const skin::SkinSurface skin(balls);
    const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, e);
    REQUIRE(ms.lines.empty());
    for (double c : {-0.5, 0.1, 0.6}) {
      CAPTURE(c);
      const auto curves = morse::level_curves(skin, ms, c);
      CHECK(curves.size() == 4);
      check_curves(skin, e, c, curves, {});
    }
  }
}

TEST_CASE("level curves: the count of a brute-force section, on rings, separate balls and crambin") {
  struct Case {
    std::string what;
    std::vector<geometry::WeightedPoint> points;
    std::size_t most = 1;  ///< the largest count some cut must show
  };
  std::vector<Case> cases;
  {
    // A ring of 12 balls (a torus: two curves where a cut crosses both sides).
    std::vector<geometry::WeightedPoint> ring;
    for (int i = 0; i < 12; ++i) {
      const double a = 2 * kPi * i / 12;
      ring.push_back({Vec3(4 * std::cos(a), 4 * std::sin(a), 0), 2 * 1.4 * 1.4});
    }
    cases.push_back({"a ring of 12 balls", ring, 2});
    // Three balls apart (three sphere-like components, no saddles) and a pair
    // joined by a neck.
    cases.push_back({"three balls apart and a joined pair",
                     {{Vec3(0, 0, 0), 2.0},
                      {Vec3(5, 0.5, 0), 2.5},
                      {Vec3(0, 5, 1), 1.5},
                      {Vec3(-6, 0, 0), 2 * 1.2 * 1.2},
                      {Vec3(-8.6, 0.3, 0), 2 * 1.2 * 1.2}}});
  }
  const skin::Molecule crambin = skin::read_molecule(std::string(SKINMESH_DATA) + "/crambin_1crn.pdb");
  cases.push_back({"crambin, probe 1.4", skin::weighted_points(crambin, 1.4)});
  cases.push_back({"crambin, probe 0", skin::weighted_points(crambin, 0.0), 2});

  std::mt19937 rng(26);
  for (const Case& cs : cases) {
    CAPTURE(cs.what);
    const skin::SkinSurface skin(cs.points);
    for (int k = 0; k < 2; ++k) {
      const Vec3 e = test::random_rotation(rng).col(2);
      const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, e);
      double lo = 1e300, hi = -1e300;
      for (const auto& p : ms.critical) lo = std::min(lo, p.height), hi = std::max(hi, p.height);
      int tried = 0;
      std::size_t most = 0;
      // In each sixth of the height range, the height farthest from the
      // critical points (in units of their rho, past their protecting spheres).
      for (int w = 0; w < 6; ++w) {
        double c = 0, best = -1e300;
        for (int i = 0; i < 64; ++i) {
          const double h = lo + (hi - lo) * (w + (i + 0.5) / 64) / 6;
          if (const double cl = morse::cut_clearance(ms, h); cl > best) best = cl, c = h;
        }
        if (best <= 0) continue;
        ++tried;
        CAPTURE(c);
        const auto curves = morse::level_curves(skin, ms, c);
        const int expected = brute_force_curve_count(skin, e, c, 0.04);
        CHECK(static_cast<int>(curves.size()) == expected);
        check_curves(skin, e, c, curves, {});
        most = std::max(most, curves.size());
      }
      CHECK(tried >= 2);
      CHECK(most >= cs.most);  // the cuts do meet several curves where the input has them
    }
  }
}

TEST_CASE(
    "cuts that detour around protecting spheres: on the skin, the plane or the circles, and the brute-force count") {
  // Heights that cross the protecting spheres of saddles (where no level cut
  // is allowed): the cut passes around each ball the plane meets, and its
  // curves bound the part below as a fine mesh of the skin counts it.
  struct Case {
    std::string what;
    std::vector<geometry::WeightedPoint> points;
  };
  std::vector<Case> cases;
  std::vector<geometry::WeightedPoint> ring;
  for (int i = 0; i < 12; ++i) {
    const double a = 2 * kPi * i / 12;
    ring.push_back({Vec3(4 * std::cos(a), 4 * std::sin(a), 0), 2 * 1.4 * 1.4});
  }
  cases.push_back({"a ring of 12 balls", ring});
  const skin::Molecule crambin = skin::read_molecule(std::string(SKINMESH_DATA) + "/crambin_1crn.pdb");
  cases.push_back({"crambin, probe 1.4", skin::weighted_points(crambin, 1.4)});
  std::mt19937 rng(2611);
  int cuts = 0, refused = 0, detoured_edges = 0, whole_circles = 0, corners = 0;
  std::size_t most_balls = 0;
  for (const Case& cs : cases) {
    CAPTURE(cs.what);
    const skin::SkinSurface skin(cs.points);
    // A mesh of the skin by the dynamic-skin baseline's static variant, an
    // algorithm that knows nothing of the Morse–Smale complex.
    dynamic::DynamicOptions dyn;
    dyn.growth = false;
    StageClock clock;
    dynamic::DynamicStats dyn_stats;
    skin::SkinVertexData vertex_data;
    const FineMesh mesh =
        fine_mesh(skin, dynamic::mesh_dynamic(skin, {}, dyn, clock, dyn_stats, vertex_data), /*levels=*/2);
    for (int k = 0; k < 2; ++k) {
      const Vec3 e = test::random_rotation(rng).col(2);
      const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, e);
      int tried = 0;
      for (std::size_t i = 0; i < ms.critical.size() && tried < 8; ++i) {
        const auto& p = ms.critical[i];
        if (p.kind != morse::CriticalKind::Saddle || !ms.live[i]) continue;
        for (const double offset : {-0.7, -0.2, 0.3}) {
          const double c = p.height + offset * ms.protect_radius[i];
          CAPTURE(c);
          const std::vector<morse::CutDetour> detours = morse::cut_detours(ms, c);
          REQUIRE(!detours.empty());  // the saddle's own ball meets the plane
          for (const auto& d : detours) most_balls = std::max(most_balls, d.balls.size());
          ++tried;
          std::vector<morse::LevelCurve> curves;
          try {
            curves = morse::cut_curves(skin, ms, c, detours);
          } catch (const GeometryError& err) {
            MESSAGE("refused: " << std::string(err.what()));
            ++refused;
            continue;
          }
          ++cuts;
          check_detoured(skin, e, c, detours, curves, detoured_edges, corners);
          for (const auto& curve : curves)
            if (std::all_of(curve.detour.begin(), curve.detour.end(), [](Index d) { return d != kInvalidIndex; }))
              ++whole_circles;
          CHECK(static_cast<int>(curves.size()) == brute_force_cut_count(mesh, e, c, detours));
        }
      }
    }
  }
  MESSAGE("cuts " << cuts << ", refused " << refused << ", edges on circles " << detoured_edges << ", whole circles "
                  << whole_circles << ", corners " << corners << ", most balls in a cluster " << most_balls);
  CHECK(cuts >= 10);
  CHECK(refused <= 1);  // one height where the plane nearly touches a circle, refused as it should be
  CHECK(detoured_edges > 0);
  CHECK(corners > 0);  // cuts that follow the union of several balls
}

TEST_CASE("a cut without detours is the level cut") {
  const skin::Molecule crambin = skin::read_molecule(std::string(SKINMESH_DATA) + "/crambin_1crn.pdb");
  const skin::SkinSurface skin(skin::weighted_points(crambin, 1.4));
  const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, Vec3(0.36, 0.48, 0.8));
  double lo = 1e300, hi = -1e300;
  for (const auto& p : ms.critical) lo = std::min(lo, p.height), hi = std::max(hi, p.height);
  const double c = 0.5 * (lo + hi);
  std::vector<morse::CutDetour> none;
  const auto a = morse::level_curves(skin, ms, c), b = morse::cut_curves(skin, ms, c, none);
  REQUIRE(a.size() == b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    CHECK(a[i].points == b[i].points);
    CHECK(std::count(a[i].detour.begin(), a[i].detour.end(), kInvalidIndex) == static_cast<long>(a[i].points.size()));
  }
}

}  // TEST_SUITE

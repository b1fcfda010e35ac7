// tests/decompose/band_test.cpp: the max-min-angle strip between a parked rim and
// an upper cut curve (decompose/band.h) against an exhaustive search over every
// strip, and the structure every strip must have: each polyline edge in
// exactly one triangle in its own direction, each connecting edge in two
// with opposite directions (a triangulated annulus), every triangle outward.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "decompose/band.h"
#include "geometry/check/mesh_checks.h"

using namespace skinmesh;

namespace {

/// A band on the unit sphere (normals = positions): the rim at height za
/// (counter-clockwise seen from +z, so that the band above is on its left)
/// and the curve at zb > za (clockwise: n × e with e = +z), with jittered
/// angles.
struct Band {
  std::vector<Vec3> rim, rim_n, curve, curve_n;
};
Band sphere_band(int n, int m, double za, double zb, double jitter, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-jitter, jitter);
  Band b;
  const double ra = std::sqrt(1 - za * za), rb = std::sqrt(1 - zb * zb);
  for (int i = 0; i < n; ++i) {
    const double t = 2 * kPi * (i + u(rng)) / n;
    b.rim.emplace_back(ra * std::cos(t), ra * std::sin(t), za);
  }
  for (int j = 0; j < m; ++j) {
    const double t = -2 * kPi * (j + u(rng)) / m + 0.3;
    b.curve.emplace_back(rb * std::cos(t), rb * std::sin(t), zb);
  }
  b.rim_n = b.rim, b.curve_n = b.curve;
  return b;
}

double min_angle_of(const Band& b, const std::vector<decompose::StripTriangle>& tris) {
  auto pos = [&](Index k) { return k < b.rim.size() ? b.rim[k] : b.curve[k - b.rim.size()]; };
  double q = 1e9;
  for (const auto& t : tris) q = std::min(q, geometry::min_angle(pos(t[0]), pos(t[1]), pos(t[2])));
  return q;
}

/// The structure of a strip: n + m triangles, outward, each rim edge i -> i+1
/// and curve edge j -> j+1 once in its own direction, every other edge once
/// each way.
void check_strip(const Band& b, const std::vector<decompose::StripTriangle>& tris) {
  const Index n = static_cast<Index>(b.rim.size()), m = static_cast<Index>(b.curve.size());
  REQUIRE(tris.size() == static_cast<std::size_t>(n + m));
  auto pos = [&](Index k) { return k < n ? b.rim[k] : b.curve[k - n]; };
  auto nor = [&](Index k) { return k < n ? b.rim_n[k] : b.curve_n[k - n]; };
  std::map<std::pair<Index, Index>, int> directed;
  for (const auto& t : tris) {
    const Vec3 nt = (pos(t[1]) - pos(t[0])).cross(pos(t[2]) - pos(t[0]));
    for (Index k : t) CHECK(nt.dot(nor(k)) > 0);
    for (int e = 0; e < 3; ++e) ++directed[{t[e], t[(e + 1) % 3]}];
  }
  auto count = [&](Index a, Index c) { return directed.count({a, c}) ? directed.at({a, c}) : 0; };
  for (Index i = 0; i < n; ++i) {
    CHECK(count(i, (i + 1) % n) == 1);
    CHECK(count((i + 1) % n, i) == 0);
  }
  for (Index j = 0; j < m; ++j) {
    CHECK(count(n + j, n + (j + 1) % m) == 1);
    CHECK(count(n + (j + 1) % m, n + j) == 0);
  }
  for (const auto& [e, c] : directed) {
    CHECK(c == 1);
    const bool polyline_edge = (e.first < n && e.second < n) || (e.first >= n && e.second >= n);
    if (!polyline_edge) CHECK(directed.count({e.second, e.first}) == 1);
  }
}

/// The sum the strip minimises among those of the best smallest angle.
double sum_of(const Band& b, const std::vector<decompose::StripTriangle>& tris) {
  auto pos = [&](Index k) { return k < b.rim.size() ? b.rim[k] : b.curve[k - b.rim.size()]; };
  double sum = 0;
  for (const auto& t : tris) {
    const double s = std::sin(geometry::min_angle(pos(t[0]), pos(t[1]), pos(t[2])));
    sum += 1 / (s * s);
  }
  return sum;
}

/// The best (smallest angle, then sum of 1 / sin² of the smallest angles)
/// over every strip that starts at rim vertex 0 and one of the curve
/// vertices within two of the one nearest to it, by enumerating all
/// C(n+m, n) strips from each start.
std::pair<double, double> brute_force_best(const Band& b) {
  const std::size_t n = b.rim.size(), m = b.curve.size();
  std::size_t nearest = 0;
  for (std::size_t j = 1; j < m; ++j)
    if ((b.curve[j] - b.rim[0]).norm() < (b.curve[nearest] - b.rim[0]).norm()) nearest = j;
  std::vector<std::size_t> starts{nearest};
  for (std::size_t d = 1; d <= 2 && 2 * d < m; ++d)
    starts.push_back((nearest + d) % m), starts.push_back((nearest + m - d) % m);
  double best = -1, best_sum = 0;
  for (std::size_t s : starts) {
    std::function<void(std::size_t, std::size_t, double, double)> go = [&](std::size_t i, std::size_t j, double q,
                                                                           double sum) {
      if (q < 0) return;
      if (i == n && j == m) {
        if (q > best || (q == best && sum < best_sum)) best = q, best_sum = sum;
        return;
      }
      const std::size_t c = (s + m - j % m) % m;
      auto quality = [&](const Vec3& x, const Vec3& y, const Vec3& z, const Vec3& nx, const Vec3& ny, const Vec3& nz) {
        const Vec3 nt = (y - x).cross(z - x);
        if (!(nt.dot(nx) > 0 && nt.dot(ny) > 0 && nt.dot(nz) > 0)) return -1.0;
        return geometry::min_angle(x, y, z);
      };
      auto cost = [](double a) { return a > 0 ? 1 / (std::sin(a) * std::sin(a)) : 0.0; };
      if (i < n) {
        const double a =
            quality(b.rim[i], b.rim[(i + 1) % n], b.curve[c], b.rim_n[i], b.rim_n[(i + 1) % n], b.curve_n[c]);
        go(i + 1, j, std::min(q, a), sum + cost(a));
      }
      if (j < m) {
        const std::size_t c1 = (s + m - (j + 1) % m) % m;
        const double a = quality(b.curve[c1], b.curve[c], b.rim[i % n], b.curve_n[c1], b.curve_n[c], b.rim_n[i % n]);
        go(i, j + 1, std::min(q, a), sum + cost(a));
      }
    };
    go(0, 0, 1e9, 0);
  }
  return {best, best_sum};
}

}  // namespace

TEST_CASE("strip triangulation: the best smallest angle and then the least sum of an exhaustive search") {
  std::mt19937 rng(26);
  for (int trial = 0; trial < 30; ++trial) {
    CAPTURE(trial);
    const int n = 3 + trial % 5, m = 3 + (trial / 5) % 5;
    const Band b = sphere_band(n, m, 0.1, 0.1 + 0.05 * (1 + trial % 3), 0.3, rng);
    const auto tris = decompose::strip_triangulation(b.rim, b.rim_n, b.curve, b.curve_n);
    const auto [brute, brute_sum] = brute_force_best(b);
    if (brute < 0) {
      CHECK(tris.empty());
      continue;
    }
    check_strip(b, tris);
    CHECK(min_angle_of(b, tris) == doctest::Approx(brute).epsilon(1e-12));
    // Among the strips of that smallest angle, the one of the least sum: the
    // triangles away from the bottleneck are as good as they can be too.
    CHECK(sum_of(b, tris) == doctest::Approx(brute_sum).epsilon(1e-9));
  }
}

TEST_CASE("strip triangulation: long loops in a corridor, and refusals") {
  std::mt19937 rng(7);
  const Band b = sphere_band(180, 211, 0.2, 0.23, 0.25, rng);
  const auto full = decompose::strip_triangulation(b.rim, b.rim_n, b.curve, b.curve_n);
  const auto narrow = decompose::strip_triangulation(b.rim, b.rim_n, b.curve, b.curve_n, 0.05);
  check_strip(b, full);
  check_strip(b, narrow);
  // The corridor holds the best strip of a uniform band.
  CHECK(min_angle_of(b, narrow) == doctest::Approx(min_angle_of(b, full)));
  CHECK(min_angle_of(b, full) > 20 * kDegree);

  // A short rim edge 0 -> 1 forces a poor triangle, the bottleneck of every
  // strip: the others must still follow the band, not twist across it
  // (which every strip above that bottleneck would be allowed to).
  Band pinched = b;
  pinched.rim[1] = (pinched.rim[0] + 0.1 * (pinched.rim[1] - pinched.rim[0])).normalized();
  pinched.rim_n[1] = pinched.rim[1];
  const auto tris = decompose::strip_triangulation(pinched.rim, pinched.rim_n, pinched.curve, pinched.curve_n, 0.05);
  check_strip(pinched, tris);
  CHECK(min_angle_of(pinched, tris) < 10 * kDegree);
  std::size_t poor = 0;
  for (const auto& t : tris) {
    auto pos = [&](Index k) { return k < pinched.rim.size() ? pinched.rim[k] : pinched.curve[k - pinched.rim.size()]; };
    if (geometry::min_angle(pos(t[0]), pos(t[1]), pos(t[2])) < 20 * kDegree) ++poor;
  }
  CHECK(poor <= 2);

  // Normals pointing inwards on the curve: no strip faces outwards.
  Band flipped = b;
  for (Vec3& x : flipped.curve_n) x = -x;
  CHECK(decompose::strip_triangulation(flipped.rim, flipped.rim_n, flipped.curve, flipped.curve_n).empty());
  CHECK_THROWS_AS(
      decompose::strip_triangulation({Vec3::Zero(), Vec3::UnitX()}, {Vec3::UnitZ(), Vec3::UnitZ()}, b.curve, b.curve_n),
      std::invalid_argument);
}

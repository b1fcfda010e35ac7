// decompose/work.cpp: the predicted work by height (decompose/work.h).
// Notes: papers/decompose/README.md ("The cuts")
#include "decompose/work.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>
#include <stdexcept>

#include "core/parallel.h"

namespace skinmesh::decompose {

namespace {

/// n directions spread evenly over the unit sphere (the Fibonacci sphere):
/// z at the midpoints of n equal bands, longitudes by the golden angle.
std::vector<Vec3> fibonacci_directions(int n) {
  std::vector<Vec3> d;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < n; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    d.emplace_back(r * std::cos(golden * k), r * std::sin(golden * k), z);
  }
  return d;
}

/// The non-bounding vertices of the tetrahedra around vertex v (its star,
/// by a search over the tetrahedra that hold v), into `out` (cleared).
void star_vertices(const geometry::RegularTriangulation& rt, Index v, std::vector<Index>& tets,
                   std::vector<Index>& out) {
  out.clear();
  tets.clear();
  const Index t0 = rt.vertex_tet(v);
  if (t0 == kInvalidIndex) return;
  tets.push_back(t0);
  for (std::size_t k = 0; k < tets.size(); ++k) {
    const Index t = tets[k];
    const std::array<Index, 4>& tv = rt.tet(t);
    for (int i = 0; i < 4; ++i) {
      if (tv[i] == v) continue;  // the face opposite v does not hold v
      if (!rt.is_bounding(tv[i])) out.push_back(tv[i]);
      const Index n = rt.neighbor(t, i);
      if (n != kInvalidIndex && std::find(tets.begin(), tets.end(), n) == tets.end()) tets.push_back(n);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace

double WorkProfile::total() const {
  std::uint64_t n = 0;
  for (std::uint64_t c : count) n += c;
  return samples_per_patch > 0 ? static_cast<double>(n) / samples_per_patch : 0.0;
}

double WorkProfile::height_at(double share) const {
  std::uint64_t n = 0;
  for (std::uint64_t c : count) n += c;
  const double target = std::clamp(share, 0.0, 1.0) * static_cast<double>(n);
  double below = 0;
  for (std::size_t b = 0; b < count.size(); ++b) {
    const double c = static_cast<double>(count[b]);
    if (c > 0 && below + c >= target) return lo + bin * (static_cast<double>(b) + (target - below) / c);
    below += c;
  }
  return lo + bin * static_cast<double>(count.size());
}

double WorkProfile::share_below(double h) const {
  std::uint64_t n = 0;
  for (std::uint64_t c : count) n += c;
  if (n == 0) return 0;
  const double x = (h - lo) / bin;
  double below = 0;
  for (std::size_t b = 0; b < count.size() && static_cast<double>(b) < x; ++b)
    below += static_cast<double>(count[b]) * std::min(1.0, x - static_cast<double>(b));
  return below / static_cast<double>(n);
}

WorkProfile work_profile(const skin::SkinSurface& skin, const Vec3& e, int threads, int samples_per_patch, int bins) {
  if (samples_per_patch < 1 || bins < 1) throw std::invalid_argument("work_profile: samples and bins must be positive");
  const geometry::RegularTriangulation& rt = skin.triangulation();
  const std::vector<Vec3> dirs = fibonacci_directions(samples_per_patch);
  WorkProfile p;
  p.samples_per_patch = samples_per_patch;
  // Every patch point lies within its atom's sphere of radius sqrt(w/2)
  // (a cavity sphere lies inside the union of its tetrahedron's atoms').
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  const Index n_points = rt.num_input_points();
  for (Index v = 0; v < n_points; ++v) {
    if (!rt.is_vertex(v)) continue;
    const geometry::WeightedPoint& a = rt.point(v);
    const double r = std::sqrt(std::max(0.0, a.w / 2));
    lo = std::min(lo, e.dot(a.z) - r), hi = std::max(hi, e.dot(a.z) + r);
  }
  p.count.assign(static_cast<std::size_t>(bins), 0);
  if (!(lo <= hi)) return p;
  p.lo = lo;
  p.bin = std::max(hi - lo, 1e-9) / bins;
  const auto bin_of = [&](double h) {
    return static_cast<std::size_t>(std::clamp(std::floor((h - p.lo) / p.bin), 0.0, bins - 1.0));
  };

  // Blocks of consecutive atoms, then of tetrahedra, each with its own
  // histogram added to the profile as it ends: integer counts, whose sum
  // does not depend on the order.
  constexpr std::size_t kBlock = 4096;
  const std::size_t atom_blocks = (static_cast<std::size_t>(n_points) + kBlock - 1) / kBlock;
  const std::size_t tet_blocks = (static_cast<std::size_t>(rt.num_tets()) + kBlock - 1) / kBlock;
  std::mutex merge;
  parallel_for(atom_blocks + tet_blocks, thread_count(threads), 1, [&](std::size_t b) {
    std::vector<std::uint64_t> h(static_cast<std::size_t>(bins), 0);
    std::vector<Index> tets, star;
    std::vector<std::pair<Vec3, double>> planes;  // inside: n·d <= offset
    // Counts the directions d inside every plane at the height of focus + r d.
    const auto sample = [&](const Vec3& focus, double r) {
      for (const Vec3& d : dirs)
        if (std::all_of(planes.begin(), planes.end(), [&](const auto& pl) { return pl.first.dot(d) <= pl.second; }))
          ++h[bin_of(e.dot(focus + r * d))];
    };
    if (b < atom_blocks) {
      for (Index v = static_cast<Index>(b * kBlock),
                 end = static_cast<Index>(std::min<std::size_t>(n_points, (b + 1) * kBlock));
           v < end; ++v) {
        if (!rt.is_vertex(v)) continue;
        const geometry::WeightedPoint& a = rt.point(v);
        if (a.w <= 0) continue;
        const double r = std::sqrt(a.w / 2);
        // The mixed cell of v is its power cell halved towards z_v: the
        // bisector with u at (d² + w_v - w_u) / (2d) from z_v, halved.
        star_vertices(rt, v, tets, star);
        planes.clear();
        for (Index u : star) {
          const geometry::WeightedPoint& q = rt.point(u);
          const Vec3 d = q.z - a.z;
          planes.emplace_back(r * d, (d.squaredNorm() + a.w - q.w) / 4);
        }
        sample(a.z, r);
      }
    } else {
      const std::size_t first = (b - atom_blocks) * kBlock;
      const std::size_t end = std::min<std::size_t>(static_cast<std::size_t>(rt.num_tets()), first + kBlock);
      for (std::size_t t = first; t < end; ++t) {
        const std::array<Index, 4>& tv = rt.tet(static_cast<Index>(t));
        if (std::any_of(tv.begin(), tv.end(), [&](Index v) { return v == kInvalidIndex || rt.is_bounding(v); }))
          continue;
        std::array<Vec3, 4> z;
        std::array<double, 4> w;
        for (int i = 0; i < 4; ++i) z[i] = rt.point(tv[i]).z, w[i] = rt.point(tv[i]).w;
        // The orthocentre x: 2 (z_i - z_0)·(x - z_0) = |z_i - z_0|² - w_i + w_0
        // for i = 1..3, solved by Cramer's rule in cross products.
        const Vec3 a = z[1] - z[0], b = z[2] - z[0], c = z[3] - z[0];
        const Vec3 bc = b.cross(c), ca = c.cross(a), ab = a.cross(b);
        const double det = 2 * a.dot(bc);
        if (!(std::abs(det) > 0)) continue;  // a flat tetrahedron holds no cavity patch
        const Vec3 focus = z[0] + ((a.squaredNorm() - w[1] + w[0]) * bc + (b.squaredNorm() - w[2] + w[0]) * ca +
                                   (c.squaredNorm() - w[3] + w[0]) * ab) /
                                      det;
        const double power = (focus - z[0]).squaredNorm() - w[0];
        if (!(power > 0)) continue;
        const double r = std::sqrt(power / 2);
        // focus + r·dir is in the cell (the tetrahedron halved towards the
        // focus) iff focus + 2r·dir is in the tetrahedron.
        planes.clear();
        for (int i = 0; i < 4; ++i) {
          const Vec3& o = z[(i + 1) % 4];
          Vec3 n = (z[(i + 2) % 4] - o).cross(z[(i + 3) % 4] - o);
          if (n.dot(z[i] - o) > 0) n = -n;  // outward: away from the opposite vertex
          planes.emplace_back(2 * r * n, n.dot(o - focus));
        }
        sample(focus, r);
      }
    }
    const std::lock_guard<std::mutex> lock(merge);
    for (std::size_t k = 0; k < h.size(); ++k) p.count[k] += h[k];
  });
  return p;
}

}  // namespace skinmesh::decompose

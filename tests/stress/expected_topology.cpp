// tests/stress/expected_topology.cpp: brute-force dual complex (nerve of the
// restricted unshrunk balls) and its Betti numbers over Z/2
// (tests/stress/expected_topology.h). Long double throughout; coordinates are
// taken relative to the first point, which is exact for double inputs of
// comparable magnitude (so a translation by 1e6 Å costs no accuracy).
#include "tests/stress/expected_topology.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <set>
#include <unordered_map>
#include <unordered_set>

#include "skin/skin_surface.h"

namespace skinmesh::stress {

std::string Topology::text() const {
  std::string s = "(";  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on "(" + std::string
  s += std::to_string(components());
  s += ", ";
  s += std::to_string(euler());
  s += ")";
  return s;
}

std::string Topology::betti_text() const {
  return std::to_string(b0) + "/" + std::to_string(b1) + "/" + std::to_string(b2);
}

Topology from_skin_topology(const skin::SkinTopology& t) {
  return Topology{t.betti0, t.betti0 + t.betti2 - t.euler_k0, t.betti2};
}

Topology project_topology(const std::vector<geometry::WeightedPoint>& points) {
  const skin::SkinSurface surface(points);
  return from_skin_topology(skin::dual_complex_topology(surface.mixed_complex()));
}

std::size_t rank_z2(std::vector<std::vector<std::uint32_t>> columns) {
  std::unordered_map<std::uint32_t, std::size_t> pivot;  // lowest (largest) row -> column
  std::size_t rank = 0;
  std::vector<std::uint32_t> scratch;
  for (std::size_t c = 0; c < columns.size(); ++c) {
    std::vector<std::uint32_t>& col = columns[c];
    while (!col.empty()) {
      const auto it = pivot.find(col.back());
      if (it == pivot.end()) break;
      const std::vector<std::uint32_t>& other = columns[it->second];
      scratch.clear();
      std::set_symmetric_difference(col.begin(), col.end(), other.begin(), other.end(), std::back_inserter(scratch));
      col.swap(scratch);
    }
    if (!col.empty()) {
      pivot.emplace(col.back(), c);
      ++rank;
    }
  }
  return rank;
}

namespace {

using Real = long double;
using Vec = std::array<Real, 3>;

Vec sub(const Vec& a, const Vec& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Real dot(const Vec& a, const Vec& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

/// A simplex of the nerve as a sorted key: up to four 16-bit point indices.
using Key = std::uint64_t;
constexpr std::uint64_t kNone = 0xFFFF;

Key make_key(const std::uint32_t* v, int n) {
  Key k = 0;
  for (int i = 0; i < 4; ++i) k = (k << 16) | (i < n ? v[i] : kNone);
  return k;
}

/// Betti numbers b0, b1, b2 of the downward closure of the given vertex sets
/// (each closed down to its subsets of 1 to 4 elements).
Topology betti_of(const std::set<std::vector<std::uint32_t>>& sets, std::size_t counts[4]) {
  std::unordered_set<Key> seen;
  std::vector<std::vector<std::array<std::uint32_t, 4>>> simplices(4);
  for (const std::vector<std::uint32_t>& T : sets) {
    const int m = static_cast<int>(T.size());
    std::uint32_t v[4];
    // Every subset of size 1..4 of T, in lexicographic order.
    for (int size = 1; size <= std::min(m, 4); ++size) {
      std::array<int, 4> idx{0, 1, 2, 3};
      while (true) {
        for (int i = 0; i < size; ++i) v[i] = T[idx[i]];
        const Key key = make_key(v, size);
        if (seen.insert(key).second) {
          std::array<std::uint32_t, 4> s{};
          for (int i = 0; i < size; ++i) s[i] = v[i];
          simplices[size - 1].push_back(s);
        }
        int i = size - 1;
        while (i >= 0 && idx[i] == m - size + i) --i;
        if (i < 0) break;
        ++idx[i];
        for (int j = i + 1; j < size; ++j) idx[j] = idx[j - 1] + 1;
      }
    }
  }
  std::unordered_map<Key, std::uint32_t> index;
  for (int d = 0; d < 4; ++d) {
    std::sort(simplices[d].begin(), simplices[d].end());
    counts[d] = simplices[d].size();
    for (std::size_t i = 0; i < simplices[d].size(); ++i)
      index[make_key(simplices[d][i].data(), d + 1)] = static_cast<std::uint32_t>(i);
  }
  // Boundary matrices d = 1, 2, 3: column = simplex of dimension d, rows = its facets.
  std::size_t rank[4] = {0, 0, 0, 0};
  for (int d = 1; d <= 3; ++d) {
    std::vector<std::vector<std::uint32_t>> cols;
    cols.reserve(simplices[d].size());
    for (const auto& s : simplices[d]) {
      std::vector<std::uint32_t> col;
      for (int drop = 0; drop <= d; ++drop) {
        std::uint32_t f[4];
        int k = 0;
        for (int i = 0; i <= d; ++i)
          if (i != drop) f[k++] = s[i];
        col.push_back(index.at(make_key(f, d)));
      }
      std::sort(col.begin(), col.end());
      cols.push_back(std::move(col));
    }
    rank[d] = rank_z2(std::move(cols));
  }
  Topology t;
  t.b0 = static_cast<int>(counts[0] - rank[1]);
  t.b1 = static_cast<int>(counts[1] - rank[1] - rank[2]);
  t.b2 = static_cast<int>(counts[2] - rank[2] - rank[3]);
  return t;
}

}  // namespace

BruteForceTopology brute_force_topology(const std::vector<geometry::WeightedPoint>& points,
                                        const BruteForceLimits& limits) {
  BruteForceTopology out;
  const std::size_t n = points.size();
  if (n == 0) {
    out.reason = "no points";
    return out;
  }
  if (n > limits.max_points || n >= kNone) {
    out.reason = std::to_string(n) + " points > " + std::to_string(limits.max_points);
    return out;
  }
  const Real tol = limits.tolerance;
  // Centres relative to the first one (exact for doubles of similar magnitude), weights, radii.
  std::vector<Vec> x(n);
  std::vector<Real> w(n), radius(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 3; ++c) x[i][c] = static_cast<Real>(points[i].z[c]) - static_cast<Real>(points[0].z[c]);
    w[i] = points[i].w;
    radius[i] = w[i] > 0 ? std::sqrt(w[i]) : 0;
  }
  // Balls that may meet (generous slack): only cliques of this graph can be inside.
  std::vector<std::vector<char>> adjacent(n, std::vector<char>(n, 0));
  std::vector<std::vector<std::uint32_t>> neighbours(n);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j) continue;
      const Vec d = sub(x[i], x[j]);
      const Real reach = radius[i] + radius[j];
      if (dot(d, d) <= reach * reach * (1 + 1e-6L) + 1e-18L) {
        adjacent[i][j] = 1;
        neighbours[i].push_back(static_cast<std::uint32_t>(j));
      }
    }

  std::set<std::vector<std::uint32_t>> closed_sets, open_sets;
  bool gave_up = false;
  char buf[256];

  // Examines the subset sigma[0..m]; returns true if its supersets may be inside.
  std::uint32_t sigma[4];
  auto examine = [&](int m) -> bool {
    if (++out.subsets > limits.max_subsets) {
      gave_up = true;
      out.reason = "more than " + std::to_string(limits.max_subsets) + " subsets";
      return false;
    }
    const std::uint32_t i0 = sigma[0];
    // Orthocentre z = x0 + A^T lambda with G lambda = b, G = A A^T,
    // A rows a_j = x_j - x0, b_j = (|a_j|² - w_j + w0) / 2.
    Vec y{0, 0, 0};
    if (m >= 1) {
      Vec a[3];
      Real b[3], G[3][3];
      for (int j = 0; j < m; ++j) {
        a[j] = sub(x[sigma[j + 1]], x[i0]);
        b[j] = (dot(a[j], a[j]) - w[sigma[j + 1]] + w[i0]) / 2;
      }
      Real diag = 1;
      for (int j = 0; j < m; ++j) {
        for (int k = 0; k < m; ++k) G[j][k] = dot(a[j], a[k]);
        diag *= G[j][j];
      }
      if (diag == 0) return false;  // coincident centres: affinely dependent
      Real lambda[3];
      Real det;
      if (m == 1) {
        det = G[0][0];
        lambda[0] = b[0] / G[0][0];
      } else if (m == 2) {
        det = G[0][0] * G[1][1] - G[0][1] * G[1][0];
        if (det / diag < 1e-16L) return false;
        lambda[0] = (b[0] * G[1][1] - G[0][1] * b[1]) / det;
        lambda[1] = (G[0][0] * b[1] - b[0] * G[1][0]) / det;
      } else {
        auto det3 = [](Real M[3][3]) {
          return M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) - M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                 M[0][2] * (M[1][0] * M[2][1] - M[1][1] * M[2][0]);
        };
        det = det3(G);
        if (det / diag < 1e-16L) return false;
        for (int c = 0; c < 3; ++c) {  // Cramer's rule
          Real M[3][3];
          for (int r = 0; r < 3; ++r)
            for (int k = 0; k < 3; ++k) M[r][k] = k == c ? b[r] : G[r][k];
          lambda[c] = det3(M) / det;
        }
      }
      for (int j = 0; j < m; ++j)
        for (int c = 0; c < 3; ++c) y[c] += lambda[j] * a[j][c];
      if (m >= 2 && det / diag < 1e-9L) {
        const Real p_flat = dot(y, y) - w[i0];
        if (p_flat <= 1e-6L * (dot(y, y) + w[i0]) && !out.near_degenerate) {
          out.near_degenerate = true;
          std::snprintf(buf, sizeof buf, "nearly flat %d-simplex (relative det %.3Lg) with orthocentre inside", m,
                        det / diag);
          out.near_reason = buf;
        }
      }
    }
    const Vec z{x[i0][0] + y[0], x[i0][1] + y[1], x[i0][2] + y[2]};
    const Real p = dot(y, y) - w[i0];  // π_σ(z)
    const Real scale = dot(y, y) + w[i0];
    if (p > tol * scale) return p <= 1e-6L * scale;  // not inside; supersets only if nearly
    // Unattached? Every other point k has π_k(z) >= p (ties join the set).
    std::vector<std::uint32_t> T(sigma, sigma + m + 1);
    for (std::uint32_t k : neighbours[i0]) {
      if (std::find(sigma, sigma + m + 1, k) != sigma + m + 1) continue;
      const Vec dk = sub(z, x[k]);
      const Real pk = dot(dk, dk) - w[k];
      const Real sk = dot(dk, dk) + w[k] + scale;
      if (pk - p < -tol * sk) return true;  // attached: k is closer in power distance
      if (pk - p <= tol * sk) T.push_back(k);
    }
    if (T.size() > static_cast<std::size_t>(m + 1)) {
      ++out.tie_sets;
      out.largest_tie_set = std::max(out.largest_tie_set, T.size());
    }
    if (T.size() > limits.max_tie_set) {
      gave_up = true;
      out.reason = std::to_string(T.size()) + " points tied at one orthocentre > " + std::to_string(limits.max_tie_set);
      return false;
    }
    std::sort(T.begin(), T.end());
    if (std::abs(p) <= tol * scale && !out.near_degenerate) {
      out.near_degenerate = true;
      std::snprintf(buf, sizeof buf, "orthocentre of a %d-simplex on its balls: pi = %.3Lg Å², relative %.3Lg", m, p,
                    p / scale);
      out.near_reason = buf;
    }
    closed_sets.insert(T);
    if (p < -tol * scale) open_sets.insert(T);
    return true;
  };

  // Grow subsets i < j < k < l along cliques of the adjacency graph.
  for (std::uint32_t i = 0; i < n && !gave_up; ++i) {
    sigma[0] = i;
    if (!examine(0)) continue;
    for (std::uint32_t j : neighbours[i]) {
      if (j <= i || gave_up) continue;
      sigma[1] = j;
      if (!examine(1)) continue;
      for (std::uint32_t k : neighbours[j]) {
        if (k <= j || !adjacent[i][k] || gave_up) continue;
        sigma[2] = k;
        if (!examine(2)) continue;
        for (std::uint32_t l : neighbours[k]) {
          if (l <= k || !adjacent[i][l] || !adjacent[j][l] || gave_up) continue;
          sigma[3] = l;
          examine(3);
        }
      }
    }
  }
  if (gave_up) return out;
  out.closed = betti_of(closed_sets, out.simplices);
  if (open_sets == closed_sets) {
    out.open = out.closed;
  } else {
    std::size_t ignored[4];
    out.open = betti_of(open_sets, ignored);
  }
  out.computed = true;
  return out;
}

}  // namespace skinmesh::stress

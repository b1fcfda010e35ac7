// tests/stress/expected_topology.h: the topology of the skin of a set of
// weighted points, computed independently of skin/dual_complex.cpp and of the
// regular triangulation, by brute force over subsets of at most 4 weighted
// points; plus the project's own answer (skin::dual_complex_topology) for
// comparison and as the fallback.
//
// Characterisation (papers/skin/dual_complex.md; Edelsbrunner 1999): the skin
// body (shrink 1/2) is homotopy equivalent to the union of the unshrunk balls,
// hence to the nerve of the restricted balls B_i ∩ V_i (V_i the power cell
// of weighted point i), which in general position is the dual complex K0
// (alpha complex at alpha = 0). A subset σ is in that nerve iff the minimum
// of the power distance π_σ over its power face ν_σ is <= 0; the minimum is
// attained at the orthocentre z of a superset τ ⊇ σ whose orthocentre lies in
// ν_τ (every other point k has π_k(z) >= π_τ(z)) with π_τ(z) <= 0. So the
// nerve is the downward closure of those "unattached and inside" τ; a point k
// tied with τ at z (π_k(z) = π_τ(z): cospherical input, lattices, rings) is
// added to τ, and the whole tie set is closed downwards (its restricted balls
// all contain z), which is what makes the enumeration right without general
// position. Then b0, b1, b2 by ranks of boundary matrices over Z/2, and
//   components(skin) = b0 + b2,   χ(skin) = 2 (b0 − b1 + b2).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "geometry/kernel/weighted_point.h"
#include "skin/dual_complex.h"

namespace skinmesh::stress {

/// Betti numbers of the dual complex K0 (equivalently of the union of the
/// unshrunk balls, and of the skin body) and the skin topology they give.
struct Topology {
  int b0 = 0;  ///< components of the body
  int b1 = 0;  ///< independent tunnels
  int b2 = 0;  ///< cavities (voids)
  /// Number of skin components: one outer surface per body component plus one per cavity.
  int components() const { return b0 + b2; }
  /// Euler characteristic of the whole skin, 2 χ(K0) = 2 (b0 − b1 + b2).
  int euler() const { return 2 * (b0 - b1 + b2); }
  /// "(components, χ)".
  std::string text() const;
  /// "b0/b1/b2".
  std::string betti_text() const;
  bool operator==(const Topology&) const = default;
  /// Same components and χ (what a mesh can be checked against).
  bool same_skin(const Topology& o) const { return components() == o.components() && euler() == o.euler(); }
};

/// Limits of the brute force (beyond them it gives up and says why).
struct BruteForceLimits {
  std::size_t max_points = 250;          ///< more input points: skipped
  std::uint64_t max_subsets = 30000000;  ///< orthocentres computed (subsets of <= 4 points)
  std::size_t max_tie_set = 40;          ///< points tied at one orthocentre
  /// Relative tolerance of the decisive comparisons (π_σ(z) against 0,
  /// π_k(z) against π_σ(z)), relative to the sizes of the terms compared.
  long double tolerance = 1e-9L;
};

/// Result of brute_force_topology().
struct BruteForceTopology {
  bool computed = false;  ///< false: skipped, see `reason`
  std::string reason;     ///< why it was skipped
  /// The nerve with σ inside iff π_σ(z) <= +tol (closed balls) and iff
  /// π_σ(z) < −tol (open balls, shrunk by the tolerance); equal unless near_degenerate.
  Topology closed, open;
  /// Some inside test π_σ(z) <= 0 of an unattached σ was within the relative
  /// tolerance of 0, or a simplex was nearly (not exactly) affinely dependent:
  /// the answer may depend on rounding, fall back to the project's exact triangulation.
  bool near_degenerate = false;
  std::string near_reason;  ///< the first near-degenerate comparison, in words
  /// Orthocentres where a further point was tied with the simplex (cospherical
  /// inputs); handled by closing the tie set, not a reason to fall back.
  std::size_t tie_sets = 0;
  std::size_t largest_tie_set = 0;
  std::uint64_t subsets = 0;                ///< orthocentres computed
  std::size_t simplices[4] = {0, 0, 0, 0};  ///< of the closed nerve's 3-skeleton
};

/// The topology of the union of the unshrunk balls of `points` (centres Å,
/// weights Å²) by brute force over subsets of <= 4 weighted points in long
/// double: subsets are grown only while their orthocentre stays inside
/// (π increases along supersets), and an unattached test looks at every
/// other point. O(#inside subsets × n). Uses nothing of skin/ or the
/// regular triangulation.
BruteForceTopology brute_force_topology(const std::vector<geometry::WeightedPoint>& points,
                                        const BruteForceLimits& limits = {});

/// Betti numbers from the project's skin::SkinTopology (b1 = b0 + b2 − χ(K0)).
Topology from_skin_topology(const skin::SkinTopology& t);

/// The project's answer: skin::dual_complex_topology of the mixed complex of
/// the exact regular triangulation of `points` (skin::SkinSurface). Throws
/// what SkinSurface throws (InputError on a bad input).
Topology project_topology(const std::vector<geometry::WeightedPoint>& points);

/// Rank over Z/2 of a matrix given by its columns, each a sorted list of the
/// row indices of its non-zero entries (column reduction).
std::size_t rank_z2(std::vector<std::vector<std::uint32_t>> columns);

}  // namespace skinmesh::stress

// skin/dual_complex.h: the dual complex K0 (alpha shape at alpha = 0) of the
// unshrunk weighted points, and the skin topology it predicts.
// papers/skin/skin_math.md §5 "Global check"; Edelsbrunner 1999 (the skin body,
// shrink 1/2, has the homotopy type of the union of the input balls, hence of
// K0).
// Notes: papers/skin/dual_complex.md
#pragma once

#include <array>
#include <vector>

#include "skin/mixed_complex.h"

namespace skinmesh::skin {

/// Topology of the skin predicted from K0, independently of any critical point.
struct SkinTopology {
  int k0_simplices[4] = {0, 0, 0, 0};  ///< vertices, edges, triangles, tetrahedra of K0
  int euler_k0 = 0;                    ///< chi(K0)
  int betti0 = 0;                      ///< components of K0 (= of the skin body)
  int betti2 = 0;                      ///< voids of K0 (= cavities of the body)
  /// Singular input: the unattached simplices whose focus weight is exactly 0
  /// (their balls meet in exactly one point, z_X; the skin has a cone point
  /// there and its topology is not locally constant). Each entry lists the
  /// simplex's input point (atom) indices, increasing, padded with
  /// kInvalidIndex; in cell order. They are counted in K0 (closed balls), see
  /// papers/skin/dual_complex.md "Exact filtration signs". Empty for inputs in
  /// general position.
  std::vector<std::array<Index, 4>> singular_simplices;
  /// Number of simplices X not strictly attached for which some coface vertex
  /// k is exactly orthogonal to the orthosphere of X (pi_k(z_X) = w_X:
  /// cospherical input, e.g. lattices). Harmless: such X is treated as
  /// unattached, which gives the same filtration value. Statistics only.
  int orthogonal_ties = 0;
  /// chi(skin) = 2 chi(K0): the skin is the boundary of a body homotopic to K0.
  int euler_skin() const { return 2 * euler_k0; }
  /// Number of skin components: one outer surface per body component plus one
  /// per cavity (Alexander duality: the complement of |K0| has betti2 + 1 components).
  int components() const { return betti0 + betti2; }
  /// Total genus of the skin components: sum g_i = components - chi / 2.
  int total_genus() const { return components() - euler_k0; }
};

/// Builds K0 from the mixed complex's simplices with the standard filtration:
/// a simplex X has value w_X if it is unattached (pi_k(z_X) >= w_X for every
/// vertex k of every coface) and otherwise the minimum value of its cofaces;
/// X is in K0 iff its value <= 0 (papers/skin/skin_math.md §5). Both tests are
/// exact predicates on the triangulation's weighted points
/// (geometry/kernel/orthosphere_predicates.h), so the result does not depend on
/// rounding, however flat the simplices; exact ties are resolved as documented
/// on singular_simplices and orthogonal_ties. Simplices with a bounding point
/// are never in K0. Counts components and voids with union–find. The
/// membership tests run on up to `threads` threads (0: every core); the
/// result, its lists' order included, does not depend on the count.
SkinTopology dual_complex_topology(const MixedComplex& mc, int threads = 1);

}  // namespace skinmesh::skin

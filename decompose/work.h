// decompose/work.h: the meshing work the skin predicts, by height — what the
// cut choice balances across regions (papers/decompose/README.md, "The cuts").
// Notes: papers/decompose/README.md
#pragma once

#include <vector>

#include "core/types.h"
#include "skin/skin_surface.h"

namespace skinmesh::decompose {

/// The skin's predicted work below each height: a histogram of the integral
/// of 1/rho² over the skin's sphere patches (dimensionless: a patch's share
/// of the unit sphere's 4 pi, its solid angle seen from its focus, since rho
/// is the patch's radius there), by the height e·x of the patch point. The
/// mesh of a patch has about that integral over epsilon² triangles (edges
/// of a few epsilon · rho, Cheng & Shi §4's [L] and [U]), so equal shares of
/// it are regions of about equal numbers of triangles and of sweep work.
/// The hyperboloid patches (the necks) are left out: their pieces are
/// bounded by Voronoi facets the estimate would have to build.
struct WorkProfile {
  double lo = 0;   ///< the lowest bin's lower height (Å)
  double bin = 1;  ///< the bins' width (Å)
  /// Per bin, the sampled directions of patch points in it (each worth
  /// 4 pi / samples_per_patch of solid angle); integers, so the profile does
  /// not depend on the thread count.
  std::vector<std::uint64_t> count;
  /// Directions sampled per patch.
  int samples_per_patch = 0;

  /// The whole skin's predicted work, in units of 4 pi (about the number of
  /// exposed unit spheres).
  double total() const;
  /// The height below which `share` (in [0, 1]) of the predicted work lies,
  /// linear within a bin. Pre: count not all zero.
  double height_at(double share) const;
  /// The share of the predicted work below height h, linear within a bin.
  double share_below(double h) const;
};

/// The predicted work of `skin` along the unit direction `e`, on up to
/// `threads` threads (<= 0: every core; the profile does not depend on the
/// count). Each atom's sphere patch (the sphere of radius sqrt(w/2) about the
/// atom, inside its mixed cell: the power cell halved towards the atom) and
/// each tetrahedron's cavity sphere patch (radius sqrt(pi/2) about the
/// orthocentre for a positive orthosphere weight pi, inside the tetrahedron
/// halved towards it) is sampled in `samples_per_patch` fixed directions (a
/// Fibonacci sphere), each direction inside the cell counted at its point's
/// height. Costs per atom its star in the regular triangulation (about 15
/// neighbours) times the directions: 0.07 s for maltoporin (10,123 atoms) on one
/// thread, 1.3 % of its mesh on two.
/// Pre: e has unit length; samples_per_patch >= 1.
WorkProfile work_profile(const skin::SkinSurface& skin, const Vec3& e, int threads, int samples_per_patch = 32,
                         int bins = 4096);

}  // namespace skinmesh::decompose

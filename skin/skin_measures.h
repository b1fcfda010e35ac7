// skin/skin_measures.h: the area and the enclosed volume of the skin surface,
// integrated over the exact sphere and hyperboloid patches (not a mesh).
// Derivation and accuracy: papers/skin/skin_measures.md.
#pragma once

#include <array>
#include <vector>

#include "core/types.h"
#include "geometry/kernel/weighted_point.h"
#include "skin/mixed_complex.h"
#include "skin/skin_surface.h"

namespace skinmesh::skin {

/// What one mixed cell's patch contributes to the skin's measures.
struct PatchMeasure {
  /// Area (Å²) of the patch piece {x in mu_X : f_X(x) = 0}.
  double area = 0;
  /// (1/3) ∫ x·n dA over the piece (Å³), x relative to the origin of the
  /// complex's coordinates and n the outward normal. Summed over all cells it
  /// is the enclosed volume (divergence theorem); one cell's value depends on
  /// the origin.
  double volume = 0;
  /// True if the piece is not empty.
  bool nonempty = false;
};

/// The measures of the whole skin.
struct SkinMeasures {
  /// Area of the skin (Å²).
  double area = 0;
  /// Enclosed volume (Å³): the volume of the body bounded by the skin, so
  /// cavities (voids inside the molecule) count negative.
  double volume = 0;
  /// Number of mixed cells whose patch piece is not empty.
  Index patch_cells = 0;
};

/// The patch piece of cell c integrated exactly in the meridian direction and
/// by adaptive Gauss–Kronrod quadrature in the azimuth, between the azimuths
/// where the piece's boundary has a corner or turns (papers/skin/skin_measures.md).
/// Relative accuracy about 1e-10 of the piece's area. Zero for cells that
/// touch a bounding point (they hold no skin). Throws GeometryError if the
/// cell's planes do not bound the piece (a broken complex).
PatchMeasure patch_measure(const MixedComplex& mc, Index c);

/// The areas (Å²) of the parts of cell c's patch piece nearest, in power
/// distance, to each vertex of the cell's simplex: entry i for the simplex's
/// vertex i, entries past its dimension 0. This is the attribution of
/// SkinSurface::atom_of() (a sphere patch to its atom; a hyperboloid or
/// concave sphere patch cut by the power bisectors of the simplex's atoms),
/// integrated as patch_measure() with the bisectors as further planes; the
/// entries sum to patch_measure(mc, c).area up to the quadrature's accuracy
/// (papers/skin/atom_areas.md). Errors as patch_measure().
std::array<double, 4> patch_atom_areas(const MixedComplex& mc, Index c);

/// Area and enclosed volume of the skin, the sum of patch_measure() over all
/// cells in cell order (the result does not depend on `threads`; threads <= 0
/// uses every core). Accuracy: about 1e-10 relative (papers/skin/skin_measures.md,
/// with measured times: about 0.1 ms per non-empty patch, thread, e.g. 1.5 s
/// for maltoporin's 10,123 atoms at probe 1.4 on one thread). The volume is
/// taken about the origin of the skin's coordinates: keep them local
/// (local_frame_centre) for inputs far from the origin. Errors as
/// patch_measure().
SkinMeasures skin_measures(const SkinSurface& skin, int threads = 1);

/// The same for weighted points (centres in Å, weights in Å²), in the local
/// frame of local_frame_centre(), as the mesher sees them; the skin, too, is
/// built on `threads` threads. Throws InputError for an empty or non-finite
/// input.
SkinMeasures skin_measures(const std::vector<geometry::WeightedPoint>& points, int threads = 1);

/// The skin's area per input point (Å²; one entry per point of the skin's
/// regular triangulation, in input order; 0 for redundant points): the sum
/// of patch_atom_areas() over all cells in cell order, so the result does not
/// depend on `threads` (<= 0: every core). The entries sum to
/// skin_measures().area within about 1e-10 relative; the cost is about 1.6
/// times skin_measures()' (maltoporin: 1.49 against 0.93 s on 2 threads;
/// papers/skin/atom_areas.md). Errors as patch_measure().
std::vector<double> atom_areas(const SkinSurface& skin, int threads = 1);

/// The same for weighted points (centres in Å, weights in Å²), in the local
/// frame of local_frame_centre(). Throws InputError for an empty or
/// non-finite input, as skin_measures() does.
std::vector<double> atom_areas(const std::vector<geometry::WeightedPoint>& points, int threads = 1);

}  // namespace skinmesh::skin

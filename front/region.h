// front/region.h: the part of the skin one sweep meshes, as a value the sweep
// is handed — where its front starts (the lower cut curves, beside the bowls
// at the minima it owns), which critical points it owns, and where its front
// stops (parked below an upper cut, level or detoured). The whole skin is the
// default region, and its sweep is Algorithm 1 of Cheng & Shi 2004 §4.1
// unchanged. The band left open between a region's parked rims and its upper
// cut is closed by the strip of decompose/band.h.
// Notes: papers/decompose/README.md ("Regions", "The sweep of a region")
#pragma once

#include <limits>
#include <vector>

#include "core/errors.h"
#include "front/sweep.h"
#include "morse/level_curves.h"

namespace skinmesh::front {

/// One region of the skin F for one sweep: with level cuts the region
/// F ∩ {lower <= e·x <= upper} (e the complex's height direction); with
/// detoured cuts, the part between the cut curves, its critical points given
/// by `owns`; with `owns` alone, a group of components. Default-constructed,
/// the whole skin.
struct Region {
  /// Height of the lower cut (Å); -infinity: the region starts below the skin
  /// (no lower cut, no lower curves).
  double lower = -std::numeric_limits<double>::infinity();
  /// The closed curves of F ∩ {e·x = lower}, as morse::level_curves() returns
  /// them (oriented by n × e, at least three samples each). Every one becomes
  /// a loop of the initial front; their samples are the region's lower boundary
  /// vertices, in this order.
  std::vector<morse::LevelCurve> lower_curves;
  /// Height of the upper cut (Å); +infinity: the region goes over the skin's top
  /// (no parking; every hole is sealed).
  double upper = std::numeric_limits<double>::infinity();
  /// The closed curves of F ∩ {e·x = upper}, as morse::level_curves()
  /// returns them; may be left empty. Given, they tell the parked rims from
  /// stray holes: each curve keeps the open loop with parked vertices that
  /// lies nearest to it (RegionResult::rim_curve), and every other such loop
  /// (a hole the front pinched off in the band, no critical point inside) is
  /// sealed like any hole.
  std::vector<morse::LevelCurve> upper_curves;
  /// A departure vertex v higher than upper - park_factor · r_v · sin(theta_v)
  /// (r_v its tangent-disc radius, theta_v the angle between its normal and
  /// e: about park_factor · r_v from the cut along the skin) is parked
  /// instead of creeping: no fan then reaches above about upper -
  /// (park_factor - 1) · r · sin(theta). At least 1. [derived] 2: the band
  /// left between the parked rim and the upper cut is one to two edge lengths
  /// wide along the skin, the width of one strip of triangles.
  double park_factor = 2;
  /// With cuts that detour around critical points (morse::cut_curves): per
  /// critical point, 1 if it lies in this region's part of the skin (between
  /// the cuts, or in a cluster of balls a cut gives to this region); empty for
  /// level cuts (by height).
  std::vector<char> owns;
  /// The clusters of balls the upper cut passes around (empty for a level
  /// cut): near them a departure vertex parks by its distance to
  /// upper_curves, which must then be given.
  std::vector<morse::CutDetour> upper_detours;
  /// A departure vertex in the hold region of a live critical point the region
  /// owns is held (and the saddle bridged, the maximum sealed) before the
  /// parking test. Needed where the cuts detour: no height window keeps the
  /// critical points away from such a cut, and a saddle whose ball misses
  /// the plane can lie in the band under it (crambin at probe 0: 0.05 Å
  /// below, 0.32 and 0.36 Å from two curves of the cut). Parked around, it
  /// joined the two curves' rims into one loop
  /// (papers/decompose/README.md, "The sweep of a region"). A saddle still
  /// holding one side when the queue runs empty is then bridged to the
  /// parked vertices near it (its other side parked before reaching it).
  /// Off for level cuts, whose window keeps every critical point two disc
  /// radii below them, so their meshes stay as they were.
  bool holds_before_parking = false;
};

/// The mesh of one region: a compact triangulated surface whose boundary is
/// the lower cut curves' samples and the parked rims below the upper cut.
struct RegionResult {
  /// The region's triangles, counter-clockwise about the outward normal, every
  /// vertex on the skin, garbage-collected, with the vertex properties of
  /// SweepResult::mesh. Vertices 0 .. (the samples' total) - 1 are the lower
  /// curves' samples in Region::lower_curves' order.
  geometry::SurfaceMesh mesh;
  SweepStats stats;
  /// Per lower curve, its sample vertices in curve order: one boundary loop of
  /// the mesh each, traversed in that order (the part below the cut, meshed
  /// by the region below, on its left).
  std::vector<std::vector<Index>> lower_loops;
  /// The boundary loops that reach the upper cut's band (each has a parked
  /// vertex), in boundary order (the band on their left, seen from outside).
  std::vector<std::vector<Index>> upper_rims;
  /// With Region::upper_curves: for each rim, the index of its upper curve
  /// (one rim per curve); empty otherwise.
  std::vector<std::size_t> rim_curve;
  /// How many of the mesh's vertices were parked.
  std::size_t parked = 0;
};

/// A failure of sweep_region() at the region's lower cut: the ghost strip below a
/// lower curve folds or meets a critical point, a repair of the front
/// reached below the cut, or a lower curve is no longer one boundary loop.
/// The decomposed sweep drops that cut, not the upper one: merging the region
/// with the one above would meet the same lower cut again.
class LowerCutError : public TopologyError {
 public:
  using TopologyError::TopologyError;
};

/// Algorithm 1 (Cheng & Shi §4.1) over a region without cuts: the critical
/// points `region.owns` gives (a group of whole components of the skin) get
/// their bowls and holds, the others nothing, and the seal closes every
/// hole. With an empty `owns` this is sweep_mesh() of the whole skin. The
/// result is sweep_mesh()'s (not garbage-collected). Throws
/// std::invalid_argument if the region has a cut (a finite lower or upper
/// height, or curves) or an `owns` of the wrong length; otherwise as
/// sweep_mesh().
SweepResult sweep_mesh(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const Region& region,
                       const SweepOptions& opt = {}, const skin::RunContext& run = {});

/// Meshes the region by Algorithm 1 (Cheng & Shi §4.1) from an initial front of
/// the region's lower cut curves and of bowls at the minima strictly inside
/// (lower, upper); a ghost strip of triangles below each lower curve (deleted
/// at the end) makes the curve a front like a bowl's rim. Departure vertices
/// near the upper cut are parked; the seal closes every hole but the parked
/// rims. Pre: lower < upper are regular values of the height on the skin,
/// clear of every protecting sphere by a few disc radii
/// (papers/decompose/README.md, "The cuts"). Throws std::invalid_argument for
/// lower >= upper, park_factor < 1, a curve of fewer than three samples or
/// without rho and cells per sample, a region thinner than (park_factor + 1) r
/// at a lower sample (r its disc radius: the region would be all band there),
/// an `owns` of the wrong length or detours without upper curves;
/// LowerCutError where the lower cut fails (above); TopologyError (besides
/// sweep_mesh's) if a hole without a parked vertex was left open, or (with
/// upper curves) an upper curve has no rim; GeometryError if a ghost vertex
/// cannot be projected.
RegionResult sweep_region(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const Region& region,
                          const SweepOptions& opt = {}, const skin::RunContext& run = {});

}  // namespace skinmesh::front

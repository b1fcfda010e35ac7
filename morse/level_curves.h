// morse/level_curves.h: the level curves of the height function on the skin —
// the cut curves of the decomposed sweep (papers/mesher/decomposition.md,
// "Cut curves"): every closed curve of F ∩ {e·x = c} at a regular value c,
// found from seeds that the Morse–Smale complex's integral lines give, traced
// by a predictor–corrector on the two equations f = 0 and e·x = c, and sampled
// at spacings set by the local length scale rho.
// Notes: papers/morse/level_curves.md
#pragma once

#include <vector>

#include "core/types.h"
#include "morse/morse_smale_complex.h"
#include "skin/skin_surface.h"

namespace skinmesh::morse {

/// One closed level curve, sampled: consecutive samples (cyclically, the last
/// joined to the first) are its edges. Every sample lies on the skin and on
/// the plane e·x = c to rounding. Orientation: the tangent n × e, so that the
/// part of the skin below the cut lies on the left seen from outside — the
/// orientation of the sweep's front as the boundary of the part meshed below.
struct LevelCurve {
  std::vector<Vec3> points;  ///< samples (Å), in the skin's coordinates
  std::vector<double> rho;   ///< local length scale at each sample (Å)
  std::vector<Index> cells;  ///< mixed cell of each sample
  double length = 0;         ///< length of the traced curve (Å), before sampling
};

/// Tuning of level_curves(); every length is a multiple of the local length
/// scale rho (papers/morse/level_curves.md says where each comes from).
struct LevelCurveOptions {
  /// Sample spacing along the curve, spacing · rho. [derived] The sweep's
  /// tangent-disc radius (SweepOptions::disc_factor, 0.185): the cut's samples
  /// become front edges of the slab above and of the slab below, as long as
  /// the fans' edges. Spacings come out in [0.75, 1] · spacing · rho (at least
  /// three samples per curve), inside [L]'s bound 2C/Q = 0.097 for the
  /// default constants.
  double spacing = 0.185;
  /// Step of the tracer, trace_step · rho · sin(theta), theta the angle between
  /// the skin normal and e: the curve's curvature is at most 1 / (rho sin
  /// theta) (papers/morse/level_curves.md), so the chord's distance from the
  /// curve stays below trace_step² / 8 · rho sin theta. [derived]
  double trace_step = 0.05;
  /// A seed within seed_tolerance · rho of a traced curve lies on it.
  /// [derived: far above the chord error, 3e-4 rho, far below the distance
  /// between two curves of a non-singular skin away from critical points]
  double seed_tolerance = 0.005;
  /// The tracer stops with GeometryError where sin(theta) falls below this:
  /// the cut passes through or next to a critical point (c is not regular).
  double min_sine = 1e-4;
};

/// The closed curves of the skin's level set F ∩ {e·x = c}, e = the complex's
/// height direction (unit), c in Å (the skin's coordinates). Each curve is
/// found once: seeds are the crossings of the level c by the complex's
/// integral lines (every arc of the Reeb graph that spans c and has a saddle at
/// one end is crossed by one of them) and, for a minimum below c at which no
/// descending line ends (a sphere-like component without saddles), by an
/// ascent from it; a seed already on a traced curve is skipped. Curves come in
/// the order of their first seeds (the complex's line order, then the
/// minima's): deterministic, and the same for every thread count.
/// Pre: c is a regular value: no critical point of h on F at height c (keep
/// it clear of every protecting sphere, cut_clearance()). Throws GeometryError
/// if a curve passes within min_sine of a critical point, if a projection onto
/// the curve fails, or if a curve does not close within a number of steps
/// bounded by the input's size.
std::vector<LevelCurve> level_curves(const skin::SkinSurface& skin, const MorseSmaleComplex& ms, double c,
                                     const LevelCurveOptions& opt = {});

/// How far the height c stays from the critical points: the minimum over the
/// critical points p of (|h(p) - c| - s_p) / rho_p, s_p the protecting radius
/// (Å) and rho_p the local length scale at p. Positive: c lies outside every
/// protecting sphere's height range; +infinity without critical points.
double cut_clearance(const MorseSmaleComplex& ms, double c);

}  // namespace skinmesh::morse

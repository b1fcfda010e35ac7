// morse/level_curves.h: the level curves of the height function on the skin —
// the cut curves of the decomposed sweep (papers/decompose/README.md,
// "The cuts"): every closed curve of F ∩ {e·x = c} at a regular value c,
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

/// One closed curve of a cut, sampled: consecutive samples (cyclically, the
/// last joined to the first) are its edges. Every sample lies on the skin,
/// and on the plane e·x = c or (on a detour, cut_curves()) on a ball's
/// sphere, to rounding. Orientation: the part of the skin below the cut lies
/// on the left seen from outside (the tangent n × e on the plane) — the
/// orientation of the sweep's front as the boundary of the part meshed below.
struct LevelCurve {
  std::vector<Vec3> points;  ///< samples (Å), in the skin's coordinates
  std::vector<double> rho;   ///< local length scale at each sample (Å)
  std::vector<Index> cells;  ///< mixed cell of each sample
  /// Per edge (sample i to i + 1, cyclically): the detour (an index into
  /// the detours cut_curves() was given) along whose boundary it runs, and
  /// the ball of that detour whose circle it follows; kInvalidIndex for both
  /// on the level set.
  std::vector<Index> detour;
  std::vector<Index> ball;
  double length = 0;  ///< length of the traced curve (Å), before sampling
};

/// One ball of a detour: a critical point's protecting sphere widened by the
/// margin (CutDetourOptions).
struct DetourBall {
  Vec3 center = Vec3::Zero();      ///< the critical point (Å), on the skin
  double radius = 0;               ///< Å: (1 + margin) s_p, at most rho(center) / 2 with the defaults
  Index critical = kInvalidIndex;  ///< the critical point
};

/// A cluster of balls the cut passes around (papers/morse/level_curves.md,
/// "Cuts that detour"): balls that overlap, each holding a critical point's
/// protecting sphere. The cut follows the boundary of their union on F (arcs
/// of their circles F ∩ S(q, R)) instead of the level set inside it, on the
/// side that puts the whole union into one slab: the upper one if `upper`,
/// else the lower one.
struct CutDetour {
  std::vector<DetourBall> balls;
  bool upper = false;
};

/// Tuning of cut_detours().
struct CutDetourOptions {
  /// Each critical point p gets a ball of radius (1 + margin) s_p, s_p its
  /// protecting radius (0.25 rho_p by default, so the ball is at most rho_p
  /// / 2 wide, and the skin meets it in one disc: papers/morse/level_curves.md).
  /// The cut stays margin · s_p outside every protecting sphere.
  double margin = 0.1;
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

/// The cuts at height c that detour around the clusters of balls `detours`
/// (as cut_detours() makes them: no two clusters' balls overlap, each ball
/// centred on the skin and at most half the local length scale at its centre
/// wide): the boundary, on F, of the part below the cut, ({h <= c} minus the
/// unions that go up) plus the unions that go down. Each closed curve is made
/// of stretches of the level set outside the balls and arcs of the balls'
/// circles F ∩ S(q, R), joined at junctions (points on F and on two of the
/// plane and the spheres, which are samples); it is oriented with that part
/// on its left seen from outside (n × e on the level set). Whole loops of a
/// union's boundary come first (in the detours' order), then the curves with
/// junctions (in the order of their first junction), then the level curves
/// that meet no ball (as level_curves() orders them). Without detours this
/// is level_curves(), sample for sample.
/// Pre: no critical point of h on F at height c outside the balls. Throws
/// GeometryError as level_curves() does, and where a circle meets the plane
/// or another circle too obliquely, a stretch between two junctions is
/// shorter than half a spacing, or the pieces do not join up.
std::vector<LevelCurve> cut_curves(const skin::SkinSurface& skin, const MorseSmaleComplex& ms, double c,
                                   const std::vector<CutDetour>& detours, const LevelCurveOptions& opt = {});

/// The detours a cut at height c needs: every critical point p (live or
/// cancelled) whose ball of radius (1 + margin) s_p meets the plane, in
/// clusters of overlapping balls together with every ball (meeting the
/// plane or not) that overlaps one of theirs. A cluster goes up if the mean
/// height of its critical points is above c (decompose::choose_cuts then sends
/// up every cluster whose union the level set enters as well).
/// Deterministic: clusters in the order of their first critical point, balls
/// in the critical points' order.
std::vector<CutDetour> cut_detours(const MorseSmaleComplex& ms, double c, const CutDetourOptions& opt = {});

/// How far the height c stays from the critical points: the minimum over the
/// critical points p of (|h(p) - c| - s_p) / rho_p, s_p the protecting radius
/// (Å) and rho_p the local length scale at p. Positive: c lies outside every
/// protecting sphere's height range; +infinity without critical points.
double cut_clearance(const MorseSmaleComplex& ms, double c);

}  // namespace skinmesh::morse

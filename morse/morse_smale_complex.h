// morse/morse_smale_complex.h: integral lines of the height function traced
// from every saddle, the Morse–Smale complex they form, protecting spheres, and
// its simplification by arc contraction.
// Cheng & Shi 2004 §3.2 ("Morse-Smale complex", "Construction", "Elimination of
// the noisy critical points", Figure 3); papers/skin/skin_math.md §5, §6 (the
// paper's g_p is not an ascent field: we follow V - (n·V) n).
// Notes: papers/morse/morse_smale_complex.md
#pragma once

#include <array>
#include <string>
#include <vector>

#include "core/types.h"
#include "geometry/triangulation/point_grid.h"
#include "morse/critical_points.h"
#include "skin/run_context.h"
#include "skin/skin_surface.h"

namespace skinmesh::morse {

/// A piecewise-linear integral line from a saddle to the extremum it reaches.
struct IntegralLine {
  Index saddle = kInvalidIndex;  ///< index into the critical point list
  int direction = +1;            ///< +1 ascending (to a maximum), -1 descending
  std::vector<Vec3> points;      ///< on the skin, from the saddle outwards
  /// The mixed cell of each point (a cell containing it, as the tracer
  /// found it): where to start locating a point near the line.
  std::vector<Index> cells;
  Index end = kInvalidIndex;  ///< extremum reached, kInvalidIndex if the trace failed
};

/// Options of the Morse–Smale construction.
struct MorseSmaleOptions {
  /// Step h = step_factor * rho(x) of the Heun integrator
  /// (papers/skin/skin_math.md §6: 0.04–0.05).
  double step_factor = 0.04;
  /// Protecting-sphere radius r_p = protect_factor * rho(c). The paper uses the
  /// tangent-disc radius (§4.2, about 0.185–0.208 rho); we default to 0.25 rho
  /// because a fan from a vertex just outside a sphere of the paper's size can
  /// still cover the critical point (papers/front/open_questions.md Q8.1 (the protecting radius),
  /// papers/morse/morse_smale_complex.md).
  double protect_factor = 0.25;
  /// Arc contraction cancels a (saddle, extremum) pair joined by a single arc
  /// when their distance is below cancel_factor * (rho_s + rho_c): the pair is
  /// "noisy" (its basin is about one edge long, so the front covers it without
  /// a topological event). Farther pairs stay live even if their protecting
  /// spheres meet: the sweep holds front vertices at the nearest live critical
  /// point (papers/morse/morse_smale_complex.md).
  double cancel_factor = 0.1;
  /// Pairs (saddle, extremum) closer than coincident_factor · (rho_s + rho_c)
  /// are cancelled even without a traced arc between them: one step of a
  /// traced line (step_factor · rho) jumps over such an extremum, so they are
  /// one degenerate critical point for the sweep. [measured]
  double coincident_factor = 0.01;
  /// Maximum number of steps of one integral line.
  int max_steps = 20000;
  /// An integral line starts start_offset · rho_s away from its saddle, in
  /// the saddle's ascending or descending direction, pulled back onto the
  /// skin. [measured: far enough for a non-zero gradient, well inside one step]
  double start_offset = 0.01;
  /// A line has arrived at an extremum c when it is within arrival_steps
  /// steps of c (and within half the saddle's distance to c). [measured]
  double arrival_steps = 3.0;
  /// A Heun step that does not climb (descend) is halved at most this many
  /// times before the line is declared stalled. [numerical]
  int max_step_halvings = 30;
};

/// The Morse–Smale complex: critical points, the four arcs of every saddle,
/// protecting spheres, and which critical points are still live after
/// simplification.
struct MorseSmaleComplex {
  Vec3 height_direction = Vec3::UnitY();
  std::vector<CriticalPoint> critical;
  /// Protecting-sphere radius of each critical point (Å).
  std::vector<double> protect_radius;
  /// For saddle i: arcs[i] = {ascending +, ascending -, descending +, descending -}
  /// as indices into `lines` (kInvalidIndex for non-saddles).
  std::vector<std::array<Index, 4>> arcs;
  std::vector<IntegralLine> lines;
  /// False for critical points removed by arc contraction.
  std::vector<char> live;
  /// Pairs cancelled by arc contraction (saddle, extremum).
  std::vector<std::array<Index, 2>> cancelled;
  /// For a cancelled extremum x: the extremum that replaces it (the other end,
  /// at cancellation time, of its saddle's same-direction arcs; Figure 3).
  std::vector<Index> replaced_by;
  /// Pairs of live critical points whose protecting spheres still intersect.
  std::vector<std::array<Index, 2>> conflicts;

  /// Extremum at the end of arc k of saddle s after simplification (following
  /// the rerouting of Figure 3).
  Index arc_end(Index s, int k) const;
  /// Morse count of the live critical points.
  MorseCount live_count() const;
};

/// A partition of the critical points into groups that each cover whole
/// components of the skin: `group[i]` is the group of critical point i, in
/// 0 .. count - 1, numbered in the order of their first critical point.
struct ComponentGroups {
  std::vector<Index> group;
  Index count = 0;
};

/// Groups the critical points of `ms` by the skin component they lie on, so
/// that each group can be swept alone (papers/decompose/README.md,
/// "Groups of whole components"). A saddle and the extrema its integral lines reach lie on
/// one component, and on a connected surface with saddles these links join
/// every critical point (the descending lines and the maxima's discs cover
/// it); the extrema no line reaches belong to components without saddles
/// (one minimum and one maximum each) and form one more group together.
/// count = 1 (one group, the whole skin) when that reading is not safe: an
/// integral line without an end, or a group whose Morse count cannot be that
/// of whole components (no minimum or no maximum, an odd Euler
/// characteristic, or unlinked extrema not in minimum–maximum pairs).
/// Reads the lines' ends, not their polylines.
ComponentGroups component_groups(const MorseSmaleComplex& ms);

/// Traces one integral line from saddle `s` of `cps`, starting in tangent
/// direction `dir` (unit), ascending (sgn = +1) or descending (sgn = -1), by
/// Heun predictor–corrector steps with re-projection (papers/skin/skin_math.md
/// §6), until it comes within min(3h, |c - s| / 2) of an extremum c of the
/// right kind (not within its protecting sphere, which may contain the saddle
/// itself when the two are close). `extrema`, if given, is a grid of the
/// indices of the extrema of `cps` (build_morse_smale_complex passes one so
/// that the arrival test looks at nearby extrema only, not at all of them at
/// every step); without it the arrival test scans `cps`.
IntegralLine trace_integral_line(const skin::SkinSurface& skin, const Vec3& e, const std::vector<CriticalPoint>& cps,
                                 Index s, const Vec3& dir, int sgn, const MorseSmaleOptions& opt,
                                 const geometry::PointGrid* extrema = nullptr);

/// Builds the Morse–Smale complex of h(x) = e·x on the skin: critical points,
/// four integral lines per saddle, protecting spheres; then contracts arcs
/// (saddle, extremum) closer than cancel_factor (rho_s + rho_c), closest pairs
/// first, when exactly one arc joins them (Cheng & Shi §3.2, Figure 3).
/// Remaining intersections of protecting spheres are listed in `conflicts`.
/// The critical points and the integral lines (one saddle's four lines per
/// item) are computed on run.threads threads (0: every core); the complex is
/// the same for every count.
MorseSmaleComplex build_morse_smale_complex(const skin::SkinSurface& skin, const Vec3& e,
                                            const MorseSmaleOptions& opt = {}, const skin::RunContext& run = {});

}  // namespace skinmesh::morse

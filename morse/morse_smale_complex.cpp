// morse/morse_smale_complex.cpp: integral-line tracing (papers/skin/skin_math.md
// §6) and arc contraction (Cheng & Shi §3.2, Figure 3).
#include "morse/morse_smale_complex.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

#include "core/parallel.h"
#include "geometry/triangulation/point_grid.h"

namespace skinmesh::morse {

namespace {

/// Pull-back tolerance (relative to the skin's length scale) of the Heun
/// predictor in trace_integral_line(): the predictor's gradient only has to be
/// as accurate as the second-order step itself, whose error per step is about
/// (0.04 rho)^3 / rho^2; the corrector's points keep the full 1e-14.
constexpr double kPredictorTolerance = 1e-7;

/// Unit ascent direction of the height on the surface: (e - (n·e) n) / |...|
/// (papers/skin/skin_math.md §6; not the paper's g_p). Zero at critical points.
Vec3 surface_ascent(const Vec3& n, const Vec3& e) {
  const Vec3 g = e - n.dot(e) * n;
  const double len = g.norm();
  return len > 1e-300 ? Vec3(g / len) : Vec3::Zero();
}

}  // namespace

IntegralLine trace_integral_line(const skin::SkinSurface& skin, const Vec3& e, const std::vector<CriticalPoint>& cps,
                                 Index s, const Vec3& dir, int sgn, const MorseSmaleOptions& opt,
                                 const geometry::PointGrid* extrema) {
  IntegralLine line;
  line.saddle = s;
  line.direction = sgn;
  const CriticalPoint& sp = cps[s];
  const CriticalKind target = sgn > 0 ? CriticalKind::Maximum : CriticalKind::Minimum;
  Index cell = sp.cell;
  skin::SkinSample sx;  // the sample at x, from the pull-back that found x
  Vec3 x = skin.pull_back(sp.position + opt.start_offset * sp.rho * dir, cell, &sx);
  line.points.push_back(sp.position), line.cells.push_back(sp.cell);
  line.points.push_back(x), line.cells.push_back(cell);

  auto find_end = [&](const Vec3& p, double h) -> Index {
    Index best = kInvalidIndex;
    double best_d = std::numeric_limits<double>::infinity();
    auto consider = [&](std::size_t i) {
      if (cps[i].kind != target) return;
      const double d = (cps[i].position - p).norm();
      // Within arrival_steps · h, but never within half the saddle's own distance: a line
      // that starts next to an extremum must first head towards it.
      const double stop = std::min(opt.arrival_steps * h, 0.5 * (cps[i].position - sp.position).norm());
      // Ties go to the lower index, as in a scan of cps in order.
      if (d <= stop && (d < best_d || (d == best_d && static_cast<Index>(i) < best)))
        best = static_cast<Index>(i), best_d = d;
    };
    if (extrema)
      extrema->for_each_near(p, opt.arrival_steps * h, [&](Index i, const Vec3&) { consider(i); });
    else
      for (std::size_t i = 0; i < cps.size(); ++i) consider(i);
    return best;
  };

  for (int step = 0; step < opt.max_steps; ++step) {
    double h = opt.step_factor * sx.rho;
    const Index end = find_end(x, h);
    if (end != kInvalidIndex) {
      line.points.push_back(cps[end].position), line.cells.push_back(cps[end].cell);
      line.end = end;
      return line;
    }
    const Vec3 t1 = sgn * surface_ascent(sx.gradient.normalized(), e);
    bool advanced = false;
    for (int halve = 0; halve < opt.max_step_halvings && !advanced; ++halve, h *= 0.5) {
      Index c2 = sx.cell;
      skin::SkinSample sp, sn;
      // The predictor x_p: only its gradient is needed, to the integrator's own
      // accuracy (a position error d turns t2 by about d / rho).
      skin.pull_back(x + h * t1, c2, &sp, kPredictorTolerance);
      const Vec3 t2 = sgn * surface_ascent(sp.gradient.normalized(), e);
      Index c3 = c2;
      const Vec3 xn = skin.pull_back(x + 0.5 * h * (t1 + t2), c3, &sn);
      if (sgn * (e.dot(xn) - e.dot(x)) > 0) {
        x = xn;
        cell = c3;
        sx = sn;
        advanced = true;
      }
    }
    if (!advanced) break;  // flat region: the line stalled (e.g. at another saddle)
    line.points.push_back(x), line.cells.push_back(cell);
  }
  return line;
}

Index MorseSmaleComplex::arc_end(Index s, int k) const {
  const Index l = arcs[s][k];
  if (l == kInvalidIndex) return kInvalidIndex;
  Index end = lines[l].end;
  // Follow contractions: a cancelled extremum forwards to its replacement.
  for (std::size_t guard = 0; end != kInvalidIndex && !live[end]; ++guard) {
    if (guard > critical.size()) return kInvalidIndex;
    end = replaced_by[end];
  }
  return end;
}

MorseCount MorseSmaleComplex::live_count() const {
  std::vector<CriticalPoint> l;
  for (std::size_t i = 0; i < critical.size(); ++i)
    if (live[i]) l.push_back(critical[i]);
  return count_critical_points(l);
}

MorseSmaleComplex build_morse_smale_complex(const skin::SkinSurface& skin, const Vec3& e_in,
                                            const MorseSmaleOptions& opt, const skin::RunContext& run) {
  MorseSmaleComplex ms;
  const Vec3 e = e_in.normalized();
  ms.height_direction = e;
  ms.critical = critical_points(skin, e, run.threads);
  const Index n = static_cast<Index>(ms.critical.size());
  ms.protect_radius.resize(n);
  for (Index i = 0; i < n; ++i) ms.protect_radius[i] = opt.protect_factor * ms.critical[i].rho;
  ms.live.assign(n, 1);
  ms.replaced_by.assign(n, kInvalidIndex);
  ms.arcs.assign(n, {kInvalidIndex, kInvalidIndex, kInvalidIndex, kInvalidIndex});

  // The extrema in a grid for the arrival test of the lines: its queries reach
  // arrival_steps · step_factor · rho at most, so cells of that size for the
  // largest rho.
  double max_rho = 0;
  for (const CriticalPoint& c : ms.critical) max_rho = std::max(max_rho, c.rho);
  geometry::PointGrid extrema(
      std::max(opt.arrival_steps * opt.step_factor * max_rho, std::numeric_limits<double>::min()));
  for (Index i = 0; i < n; ++i)
    if (ms.critical[i].kind != CriticalKind::Saddle) extrema.insert(i, ms.critical[i].position);
  // Four integral lines per saddle: ±ascent (ascending), ±descent (descending),
  // in saddle order; the lines only read the skin, the critical points and
  // the grid, so the saddles are shared among the threads, each writing its
  // own four slots.
  std::vector<Index> saddles;
  for (Index s = 0; s < n; ++s)
    if (ms.critical[s].kind == CriticalKind::Saddle) saddles.push_back(s);
  ms.lines.resize(4 * saddles.size());
  for (std::size_t j = 0; j < saddles.size(); ++j)
    for (int k = 0; k < 4; ++k) ms.arcs[saddles[j]][k] = static_cast<Index>(4 * j + k);
  parallel_for(saddles.size(), thread_count(run.threads), 8, [&](std::size_t j) {
    const Index s = saddles[j];
    const CriticalPoint& c = ms.critical[s];
    const Vec3 dirs[4] = {c.ascent, -c.ascent, c.descent, -c.descent};
    for (int k = 0; k < 4; ++k)
      ms.lines[4 * j + k] = trace_integral_line(skin, e, ms.critical, s, dirs[k], k < 2 ? +1 : -1, opt, &extrema);
  });

  // Arc contraction: noisy (saddle, extremum) pairs joined by exactly one arc,
  // closest first; repeat until none is left.
  auto spheres_meet = [&](Index a, Index b) {
    return (ms.critical[a].position - ms.critical[b].position).norm() < ms.protect_radius[a] + ms.protect_radius[b];
  };
  auto noisy = [&](Index a, Index b) {
    return (ms.critical[a].position - ms.critical[b].position).norm() <
           opt.cancel_factor * (ms.critical[a].rho + ms.critical[b].rho);
  };
  struct Cand {
    double d;
    Index s, x;
  };
  // Coincident pairs: a saddle and an extremum closer than a small fraction
  // of rho are one degenerate (birth-death) critical point for the sweep,
  // whatever the traced lines say: the first step of a line from the saddle
  // jumps over the extremum, so no arc joins them. Positions do not change,
  // so they are found once; liveness is checked when they are used. The
  // extrema come from the grid (radius padded against rounding and bounded
  // with the largest rho of any critical point, then the exact test), in
  // increasing index per saddle, so the list is the one an
  // all-pairs scan gives.
  std::vector<Cand> coincident;
  std::vector<Index> near;
  for (Index s = 0; s < n; ++s) {
    if (!ms.live[s] || ms.critical[s].kind != CriticalKind::Saddle) continue;
    near.clear();
    constexpr double kReachRounding = 1e-9;  // [derived] the grid query must not miss a pair at the bound
    const double reach = opt.coincident_factor * (ms.critical[s].rho + max_rho) * (1 + kReachRounding);
    extrema.for_each_near(ms.critical[s].position, reach, [&](Index x, const Vec3&) { near.push_back(x); });
    std::sort(near.begin(), near.end());
    for (const Index x : near) {
      if (!ms.live[x]) continue;
      const double d = (ms.critical[s].position - ms.critical[x].position).norm();
      if (d < opt.coincident_factor * (ms.critical[s].rho + ms.critical[x].rho)) coincident.push_back({d, s, x});
    }
  }
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<Cand> cands;
    for (Index s = 0; s < n; ++s) {
      if (!ms.live[s] || ms.critical[s].kind != CriticalKind::Saddle) continue;
      for (int k = 0; k < 4; ++k) {
        const Index x = ms.arc_end(s, k);
        if (x == kInvalidIndex || !ms.live[x] || !noisy(s, x)) continue;
        cands.push_back({(ms.critical[s].position - ms.critical[x].position).norm(), s, x});
      }
    }
    cands.insert(cands.end(), coincident.begin(), coincident.end());
    std::sort(cands.begin(), cands.end(), [](const Cand& a, const Cand& b) { return a.d < b.d; });
    for (const Cand& cd : cands) {
      if (!ms.live[cd.s] || !ms.live[cd.x]) continue;
      const int base = ms.critical[cd.x].kind == CriticalKind::Maximum ? 0 : 2;
      const Index e0 = ms.arc_end(cd.s, base), e1 = ms.arc_end(cd.s, base + 1);
      if (e0 == kInvalidIndex || e1 == kInvalidIndex) continue;
      const bool coincident = cd.d < opt.coincident_factor * (ms.critical[cd.s].rho + ms.critical[cd.x].rho);
      if (coincident && e0 != cd.x && e1 != cd.x) {
        ms.live[cd.s] = ms.live[cd.x] = 0;
        ms.replaced_by[cd.x] = e0;
        ms.cancelled.push_back({cd.s, cd.x});
        changed = true;
        continue;
      }
      if (e0 == e1) continue;                  // double arc: cancelling would change the topology
      if (e0 != cd.x && e1 != cd.x) continue;  // stale after an earlier contraction
      ms.live[cd.s] = ms.live[cd.x] = 0;
      ms.replaced_by[cd.x] = e0 == cd.x ? e1 : e0;
      ms.cancelled.push_back({cd.s, cd.x});
      changed = true;
    }
  }

  // Remaining intersections between live protecting spheres.
  double max_r = 0;
  for (double r : ms.protect_radius) max_r = std::max(max_r, r);
  constexpr double kMinGridCell = 1e-6;  // Å; [derived] a guard for radii of zero, far below any sphere
  geometry::PointGrid grid(std::max(2 * max_r, kMinGridCell));
  for (Index i = 0; i < n; ++i)
    if (ms.live[i]) grid.insert(i, ms.critical[i].position);
  for (Index i = 0; i < n; ++i) {
    if (!ms.live[i]) continue;
    grid.for_each_near(ms.critical[i].position, 2 * max_r, [&](Index j, const Vec3&) {
      if (j > i && spheres_meet(i, j)) ms.conflicts.push_back({i, j});
    });
  }
  return ms;
}

ComponentGroups component_groups(const MorseSmaleComplex& ms) {
  const std::size_t n = ms.critical.size();
  ComponentGroups one;
  one.group.assign(n, 0);
  one.count = n ? 1 : 0;
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  auto find = [&](std::size_t a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  std::vector<char> linked(n, 0);
  for (const IntegralLine& line : ms.lines) {
    if (line.saddle == kInvalidIndex) continue;
    if (line.end == kInvalidIndex || line.end >= n || line.saddle >= n) return one;
    parent[find(line.saddle)] = find(line.end);
    linked[line.saddle] = linked[line.end] = 1;
  }
  // A cancelled pair is one degenerate critical point, on one component
  // (a coincident pair may have no arc between them).
  for (const std::array<Index, 2>& pair : ms.cancelled) {
    if (pair[0] >= n || pair[1] >= n) return one;
    parent[find(pair[0])] = find(pair[1]);
    linked[pair[0]] = linked[pair[1]] = 1;
  }
  // The extrema without a link: components without saddles, one group.
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::size_t rest = kNone;
  for (std::size_t i = 0; i < n; ++i) {
    if (linked[i]) continue;
    if (ms.critical[i].kind == CriticalKind::Saddle) return one;  // a saddle without lines
    if (rest == kNone)
      rest = i;
    else
      parent[find(i)] = find(rest);
  }
  ComponentGroups out;
  out.group.assign(n, kInvalidIndex);
  std::vector<Index> root_group(n, kInvalidIndex);
  for (std::size_t i = 0; i < n; ++i) {
    Index& g = root_group[find(i)];
    if (g == kInvalidIndex) g = out.count++;
    out.group[i] = g;
  }
  // Each group's Morse count must be that of whole closed surfaces.
  std::vector<std::array<std::int64_t, 3>> count(out.count, {0, 0, 0});
  for (std::size_t i = 0; i < n; ++i) ++count[out.group[i]][static_cast<int>(ms.critical[i].kind)];
  for (Index g = 0; g < out.count; ++g) {
    const auto& [minima, saddles, maxima] = count[g];
    if (minima == 0 || maxima == 0 || (minima - saddles + maxima) % 2 != 0) return one;
    if (rest != kNone && g == out.group[rest] && (saddles != 0 || minima != maxima)) return one;
  }
  return out;
}

}  // namespace skinmesh::morse

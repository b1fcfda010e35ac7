// dynamic/dynamic_skin.cpp: mesh_dynamic(), the growth schedule and the
// static variant of the dynamic-skin baseline.
// Notes: papers/dynamic/dynamic_skin.md
#include "dynamic/dynamic_skin.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/errors.h"
#include "morse/critical_points.h"
#include "skin/mixed_complex.h"
#include "skin/skin_surface.h"

namespace skinmesh::dynamic {

namespace {

/// Seeds the part of atom `atom`'s sphere {|x - z| = r} that lies in its
/// vertex mixed cell (where that sphere is the level set F_c, r² = c + w/2):
/// a Fibonacci lattice of spacing about `spacing` · r, turned by an angle
/// that depends on the atom (no two atoms share a lattice orientation).
/// Returns the number of samples added.
std::size_t seed_sphere_patch(SampleTriangulation& st, const skin::SkinSurface& skin, Index atom, double r,
                              double spacing) {
  const skin::MixedComplex& mc = skin.mixed_complex();
  const Vec3 z = skin.points()[atom].z;
  // Hexagonal lattice of spacing h: area sqrt(3)/2 h² per point.
  const double h = spacing;
  constexpr int kMinSeeds = 12;  // [measured] the fewest seeds of a sphere patch, however small
  // The golden angle and the golden ratio's fractional part (the Fibonacci lattice's turns). [derived]
  constexpr double kGoldenFraction = 0.6180339887498949;
  const int n = std::max(kMinSeeds, static_cast<int>(std::ceil(4 * kPi / (0.5 * std::sqrt(3.0) * h * h))));
  const double golden = kPi * (3 - std::sqrt(5.0));
  const double turn = 2 * kPi * std::fmod(kGoldenFraction * (atom + 1), 1.0);
  std::size_t added = 0;
  Index hint = kInvalidIndex;
  for (int k = 0; k < n; ++k) {
    const double u = 1 - (2 * k + 1) / static_cast<double>(n);
    const double s = std::sqrt(std::max(0.0, 1 - u * u));
    const double phi = golden * k + turn;
    const Vec3 x = z + r * Vec3(s * std::cos(phi), s * std::sin(phi), u);
    if (st.level_set().outside_hull(x)) continue;
    hint = mc.locate(x, hint);
    if (mc.cell(hint).dim != 0 || skin.atom_of(hint, x) != atom) continue;
    Vec3 y;
    double rho = 0;
    Index cell = hint;
    if (!st.level_set().project(x, y, cell, rho)) continue;
    if (st.add_sample(y, cell, rho, true) != kInvalidIndex) ++added;
  }
  return added;
}

/// Smallest final sphere radius sqrt(w/2) over the atoms (Å).
double smallest_sphere(const std::vector<geometry::WeightedPoint>& points) {
  double r = std::numeric_limits<double>::infinity();
  for (const auto& p : points) r = std::min(r, std::sqrt(std::max(p.w, 0.0) / 2));
  return r;
}

}  // namespace

void validate(const DynamicOptions& options) {
  if (!(options.seed_spacing > 0 && options.seed_spacing <= 1))
    throw std::invalid_argument("the seed spacing must lie in (0, 1]");
  if (!(options.max_step_motion > 0 && options.max_step_motion <= 1))
    throw std::invalid_argument("the step motion must lie in (0, 1]");
  if (!(options.rho_floor_fraction > 0 && options.rho_floor_fraction <= 1))
    throw std::invalid_argument("the rho floor fraction must lie in (0, 1]");
}

geometry::IndexedMesh mesh_dynamic(const skin::SkinSurface& skin, const skin::SizeConstants& size,
                                   const DynamicOptions& opt, StageClock& clock, DynamicStats& stats,
                                   skin::SkinVertexData& vertex_data) {
  auto lap = [&clock](const char* name) { clock.end(name); };
  auto report = [&clock](const char* name, double f) { clock.report(name, f); };
  const std::vector<geometry::WeightedPoint>& points = skin.points();
  geometry::IndexedMesh mesh;
  const std::size_t n_atoms = points.size();
  if (!opt.growth) {
    // Static variant: seed every sphere patch and the critical points of a
    // height function (every component has a lowest point), then refine.
    report("refine", 0.0);
    SampleTriangulation st(skin, 0.0, size);
    for (Index i = 0; i < n_atoms; ++i) {
      if (!(points[i].w > 0)) continue;
      if (seed_sphere_patch(st, skin, i, std::sqrt(points[i].w / 2), opt.seed_spacing) > 0) ++stats.births;
    }
    for (const morse::CriticalPoint& cp : morse::critical_points(skin, morse::default_height_direction()))
      st.add_sample(cp.position, cp.cell, cp.rho, true);
    stats.peak_samples = st.triangulation().num_vertices();
    stats.peak_tets = st.triangulation().num_tets();
    stats.converged = st.refine(opt.final_rounds);
    if (opt.observer) opt.observer("refine", st);
    stats.peak_samples = std::max<std::size_t>(stats.peak_samples, st.triangulation().num_vertices());
    stats.peak_tets = std::max<std::size_t>(stats.peak_tets, st.triangulation().num_tets());
    stats.samples = st.stats();
    stats.delaunay = st.triangulation().stats();
    lap("refine");
    mesh = st.extract(nullptr, &vertex_data);
    lap("output");
  } else {
    // Growth: the level sets F_c of the final skin function, c from the birth
    // of the largest atom to 0 (papers/dynamic/dynamic_skin.md "Growth").
    report("growth", 0.0);
    const double floor = opt.rho_floor_fraction * smallest_sphere(points);
    double wmax = 0;
    for (const auto& p : points) wmax = std::max(wmax, p.w);
    double c = std::min(0.0, -wmax / 2 + floor * floor);
    stats.start_level = c;
    SampleTriangulation st(skin, c, size);
    st.set_rho_floor(floor);
    std::vector<std::uint8_t> born(n_atoms, 0);
    std::vector<Index> ids;
    while (true) {
      // Births: every atom whose sphere at this level has radius >= floor.
      for (Index i = 0; i < n_atoms; ++i) {
        if (born[i] || !(c + points[i].w / 2 >= floor * floor)) continue;
        born[i] = 1;
        if (seed_sphere_patch(st, skin, i, std::sqrt(c + points[i].w / 2), opt.seed_spacing) > 0) ++stats.births;
      }
      st.mark_all_as_seeds();
      st.refine(opt.growth_rounds);
      if (opt.observer) opt.observer("growth", st);
      stats.peak_samples = std::max<std::size_t>(stats.peak_samples, st.triangulation().num_vertices());
      stats.peak_tets = std::max<std::size_t>(stats.peak_tets, st.triangulation().num_tets());
      if (c >= 0) break;
      // Step: no sample moves more than max_step_motion · max(rho, floor);
      // a sample moves by about dc / |grad f| = dc / (2 rho).
      ids = st.samples();
      double rmin = std::numeric_limits<double>::infinity();
      for (const Index v : ids) rmin = std::min(rmin, std::max(st.rho(v), floor));
      if (ids.empty()) rmin = floor;
      const double dc = 2 * opt.max_step_motion * rmin * rmin;
      constexpr double kLastStepSlack = 1e-12;  // [derived] a step that ends within rounding of 0 ends at 0
      const double next = c + dc >= -kLastStepSlack * dc ? 0.0 : c + dc;
      st.begin_batch();
      st.set_level(next);
      for (const Index v : ids) {
        Vec3 y;
        Index cell = st.cell(v);
        double rho = 0;
        const double limit = std::max(st.rho(v), floor);
        if (!st.level_set().project(st.position(v), y, cell, rho) || (y - st.position(v)).norm() > limit ||
            !st.move_sample(v, y, cell, rho)) {
          st.remove_sample(v);
          ++stats.lost_samples;
        }
      }
      st.end_batch();
      c = next;
      ++stats.steps;
      report("growth", 1.0 - c / stats.start_level);
    }
    lap("growth");
    report("refine", 0.0);
    st.set_rho_floor(0.0);
    st.mark_all_as_seeds();
    stats.converged = st.refine(opt.final_rounds);
    if (opt.observer) opt.observer("refine", st);
    stats.samples = st.stats();
    stats.delaunay = st.triangulation().stats();
    stats.kinetic_moves = st.triangulation().stats().kinetic_moves;
    stats.moves = st.stats().moves;
    lap("refine");
    mesh = st.extract(nullptr, &vertex_data);
    lap("output");
  }
  return mesh;
}

}  // namespace skinmesh::dynamic

// front/front_state.cpp: FrontState's constructor — the empty partial mesh
// with its per-vertex data, and the grids of the protecting spheres, of the
// vertices and of the front.
// Notes: papers/front/sweep.md
#include "front/front_state.h"
#include "skin/vertex_data.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace skinmesh::front::detail {

using morse::CriticalKind;

FrontState::FrontState(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const SweepOptions& opt)
    : skin(skin), ms(ms), opt(opt), e(ms.height_direction) {
  if (!(opt.disc_factor > opt.size.disc_factor_lower() && opt.disc_factor <= opt.size.disc_factor_upper())) {
    std::ostringstream os;
    os << "sweep: disc_factor " << opt.disc_factor << " is outside the tangent-disc window ("
       << opt.size.disc_factor_lower() << ", " << opt.size.disc_factor_upper() << "] of C = " << opt.size.C
       << ", Q = " << opt.size.Q << " (Cheng & Shi §4.2)";
    throw std::invalid_argument(os.str());
  }
  normal = mesh.add_vertex_property(skin::kVertexNormal, Vec3::Zero());
  rho = mesh.add_vertex_property(skin::kVertexRho, 0.0);
  cell = mesh.add_vertex_property(skin::kVertexCell, kInvalidIndex);
  state = mesh.add_vertex_property(kVertexState, VState::Interior);
  held_by = mesh.add_vertex_property(kVertexHeldBy, kInvalidIndex);
  stamp = mesh.add_vertex_property(kVertexStamp, 0);
  deferrals = mesh.add_vertex_property(kVertexDeferrals, 0);
  reopenings = mesh.add_vertex_property(kVertexReopenings, 0);
  const std::size_t nc = ms.critical.size();
  resolved.assign(nc, 0);
  held.resize(nc);
  double rmax = 0;
  for (std::size_t i = 0; i < nc; ++i) rmax = std::max(rmax, ms.protect_radius[i]);
  // Cells of four protecting radii: the hold query (rmax + r) then probes 1-2
  // cells per axis; the critical points are sparse, so a probe of an empty
  // cell costs more than reading a few more points ([measured]
  // papers/bench/profile.md, "After": the grids' cell sizes).
  hold_grid = std::make_unique<geometry::PointGrid>(std::max(4 * rmax, 1e-6));
  for (std::size_t i = 0; i < nc; ++i)
    if (ms.live[i] && ms.critical[i].kind != CriticalKind::Minimum)
      hold_grid->insert(static_cast<Index>(i), ms.critical[i].position);
  max_hold_radius = rmax;
  for (const auto& wp : skin.points()) rho_max = std::max(rho_max, std::sqrt(std::max(wp.w, 0.0) / 2));
  // The front grid's cells are four disc radii at the largest scale: the
  // contact query (1.5 r) then probes 1-2 cells per axis, and the front is a
  // curve, so most probed cells would be empty at a finer size. The vertex
  // grid's are one disc radius: the fan-collision query (0.5 r) reads a
  // quarter of the points per cell ([measured] papers/bench/profile.md,
  // "After": the grids' cell sizes).
  vertex_grid = std::make_unique<geometry::ErasablePointGrid>(std::max(opt.disc_factor * rho_max, 1e-6),
                                                               /*erasable=*/false);
  front_grid = std::make_unique<geometry::ErasablePointGrid>(std::max(4 * opt.disc_factor * rho_max, 1e-6));
  // A generous bound on the vertex count: 8 times what a separate sphere per
  // atom would need (4 pi / (c_r² sqrt(3)/2) vertices per sphere), times a
  // factor for the scales below the atoms' that the front has met (new_vertex).
  const double per_atom = 4 * kPi / (opt.disc_factor * opt.disc_factor * 0.866);
  base_vertex_budget = 1e5 + 8 * per_atom * static_cast<double>(skin.points().size());
  vertex_budget = static_cast<std::size_t>(base_vertex_budget);
  // Height range for progress reports.
  h_min = std::numeric_limits<double>::infinity();
  h_max = -h_min;
  for (const auto& cp : ms.critical) {
    h_min = std::min(h_min, e.dot(cp.position));
    h_max = std::max(h_max, e.dot(cp.position));
  }
}

}  // namespace skinmesh::front::detail

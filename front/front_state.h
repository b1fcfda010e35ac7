// front/front_state.h: the state of the sweep as a value — the partial mesh
// and its per-vertex data, the departure queue, the holds in protecting
// spheres and the grids that keep the front's queries local. Every operation
// of Algorithm 1 (front/operations.h) is a free function over it, so a
// FrontState can be made, inspected and driven one operation at a time (the
// tests of tests/front do), and several can exist side by side.
// Only front/*.cpp and the unit tests of tests/front include this header.
// Notes: papers/front/sweep.md
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <queue>
#include <string>
#include <utility>
#include <vector>

#include "front/region.h"
#include "front/sweep.h"
#include "geometry/kernel/tangent_angles.h"
#include "geometry/mesh/surface_mesh.h"
#include "geometry/triangulation/point_grid.h"
#include "morse/level_curves.h"

namespace skinmesh::front::detail {

using geometry::ccw_angle;
using geometry::coarse_ccw_angle;
using geometry::Face;
using geometry::Halfedge;
using geometry::pseudo_angle;
using geometry::pseudo_exceeds;
using geometry::rotate;
using geometry::SurfaceMesh;
using geometry::tangent_dir;
using geometry::Vertex;

/// Angular tolerance (radians) of the hole-wedge tests: spans that agree to
/// this are taken as equal ([derived] tangent angles are accurate to ~1e-12 rad).
inline constexpr double kWedgeTolerance = 1e-6;

/// Smallest cell of the sweep's point grids (Å): a guard for skins whose
/// largest radius is zero. [derived] far below any tangent-disc radius.
inline constexpr double kMinGridCell = 1e-6;
/// Octaves of rho per level of the sweep's grids (geometry::LeveledPointGrid).
/// [measured] two: a query's rho range (within ±28–58 % of its own) then
/// spans one or two levels, and a cell is at most four times its points'
/// scale.
inline constexpr int kGridOctaves = 2;
/// The vertex budget's floor, and its factor over the vertices that separate
/// spheres of the atoms would need (FrontState's constructor, new_vertex).
/// [measured] generous: the budget is a runaway guard, not a limit a correct
/// sweep meets.
inline constexpr double kVertexBudgetFloor = 1e5;
inline constexpr double kVertexBudgetFactor = 8;
/// Area of a fan triangle of the tangent circle over r² (a 60° triangle with
/// two sides r: sqrt(3)/2 · r² per two triangles ~ per vertex). [derived]
inline constexpr double kFanAreaPerVertex = 0.866;
/// Attempts of the normal-line projection, the bracket doubled each time,
/// before the gradient pull-back takes over (project_tangent). [measured]
inline constexpr int kProjectionAttempts = 4;
/// Relative and absolute (times the skin's length scale) slack of the
/// projection bracket, over its rounding. [derived]
inline constexpr double kBracketRelativeSlack = 1e-9;
inline constexpr double kBracketAbsoluteSlack = 1e-12;
/// Progress is reported each time another 1 % of the height range is swept.
inline constexpr double kProgressStep = 0.01;
/// Slack of ceil(theta / fan angle) (creep): a hole angle that is a multiple
/// of the fan angle up to rounding gives that multiple. [derived]
inline constexpr double kFanCountSlack = 1e-9;

/// State of a mesh vertex during the sweep.
enum class VState : std::uint8_t {
  Interior,  ///< every triangle around it is there
  Front,     ///< on the front, free to depart
  Held,      ///< on the front, stopped in a protecting sphere (or stuck)
};

/// The sweep's own per-vertex properties (the shared ones: skin/vertex_data.h).
/// The normal and rho are read at every step of the sweep, so the sweep keeps
/// them beside the cell they derive from (skin::VertexNormals), and drops them
/// with the others when it ends.
inline constexpr geometry::VertexPropertyKey<Vec3> kVertexFrontNormal{"v:front_normal"};
inline constexpr geometry::VertexPropertyKey<double> kVertexFrontRho{"v:front_rho"};
inline constexpr geometry::VertexPropertyKey<VState> kVertexState{"v:state"};
inline constexpr geometry::VertexPropertyKey<Index> kVertexHeldBy{"v:held_by"};
inline constexpr geometry::VertexPropertyKey<std::uint32_t> kVertexStamp{"v:stamp"};
inline constexpr geometry::VertexPropertyKey<std::uint8_t> kVertexDeferrals{"v:deferrals"};
inline constexpr geometry::VertexPropertyKey<std::uint8_t> kVertexReopenings{"v:reopenings"};
inline constexpr geometry::VertexPropertyKey<std::uint8_t> kVertexDepartures{"v:departures"};

/// Front geometry at a boundary vertex v: u -> v -> w with the hole on the left.
struct Corner {
  Vertex u, w;
  Halfedge in, out;
  double angle;  ///< hole angle at v (radians), measured in T_v
  Vec3 dw;       ///< unit tangent direction to w
};

/// The rails of a bridge's ladder: the inner points of its left and right
/// rails, pulled back onto the skin, with their mixed cells (empty for one row).
struct Rails {
  std::vector<Vec3> left, right;
  std::vector<Index> left_cell, right_cell;
};

/// The role a region's boundary gives a vertex (front/region.h).
enum class RegionRole : std::uint8_t {
  Inside,  ///< a vertex of the region
  Ghost,   ///< of the ghost strip below a lower cut curve: never departs, deleted at the end
  Parked,  ///< stopped below the upper cut: its loop is left open for the band
};

/// The region a sweep meshes, as the sweep reads it: the value it was handed,
/// the balls its upper cut passes around, and the role each vertex has on
/// its boundary. For the whole skin (the default Region) every test here is
/// false and every critical point is owned, so the sweep is Algorithm 1.
struct SweptRegion {
  explicit SweptRegion(Region r = {});
  Region spec;
  /// The balls of spec.upper_detours, one list, and a grid of them by radius
  /// (near_upper_detour).
  std::vector<morse::DetourBall> upper_balls;
  geometry::SizedItemGrid ball_grid;
  /// With detours, the upper curves' edges (curve, first sample), and a grid
  /// of their midpoints by half length: a vertex near a ball measures its
  /// distance to the cut's polyline over the edges near it only.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> upper_edges;
  geometry::SizedItemGrid edge_grid;
  /// Per vertex index; shorter than the vertex count: the vertices past its
  /// end are Inside.
  std::vector<RegionRole> role;
  /// True if the region owns critical point c at height h: given by `owns`,
  /// or with level cuts strictly between them. A minimum it owns gets a bowl.
  bool owns(Index c, double h) const {
    return spec.owns.empty() ? h > spec.lower && h < spec.upper : spec.owns[c] != 0;
  }
  /// True if the saddle or maximum c holds the front (level cuts: every one).
  bool holds(Index c) const { return spec.owns.empty() || spec.owns[c]; }
  RegionRole role_of(Vertex v) const { return v.idx() < role.size() ? role[v.idx()] : RegionRole::Inside; }
  bool is_ghost(Vertex v) const { return role_of(v) == RegionRole::Ghost; }
  bool is_parked(Vertex v) const { return role_of(v) == RegionRole::Parked; }
  /// Gives v the role r; `n_vertices` is the mesh's vertex count.
  void mark(Vertex v, RegionRole r, std::size_t n_vertices) {
    if (role.size() <= v.idx()) role.resize(n_vertices, RegionRole::Inside);
    role[v.idx()] = r;
  }
  /// True if the boundary loop through h has a ghost or a parked vertex: the
  /// region's boundary, which neither the seal nor a small hole may close.
  bool on_boundary(const SurfaceMesh& mesh, Halfedge h) const {
    if (role.empty()) return false;
    for (Halfedge g : mesh.boundary_loop(h))
      if (role_of(mesh.to_vertex(g)) != RegionRole::Inside) return true;
    return false;
  }
};

/// An entry of the departure queue: a min-heap on height with lazy deletion
/// by stamp (papers/front/open_questions.md Q1.2 (the departure queue)).
struct QueueEntry {
  double h;
  Index v;
  std::uint32_t stamp;
  bool operator>(const QueueEntry& o) const { return h != o.h ? h > o.h : v > o.v; }
};

/// The sweep's state. The front is the set of boundary half-edges of the
/// partial SurfaceMesh (a boundary half-edge has the hole on its left; faces
/// are counter-clockwise about the outward normal), so there is no second
/// front list to keep in sync (papers/front/open_questions.md Q1.1 (the front
/// as a data structure)).
struct FrontState {
  /// An empty mesh, the grids of the protecting spheres and of the vertices.
  /// Throws std::invalid_argument if opt.disc_factor lies outside the
  /// tangent-disc window of run.size (Cheng & Shi §4.2), or max_deferrals or
  /// max_reopenings outside [0, 255] (the width of their counters). `skin`, `ms` and
  /// `opt` must outlive the state.
  /// `region` is the part of the skin to mesh (the whole skin by default).
  FrontState(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const SweepOptions& opt,
             skin::RunContext run = {}, Region region = {});

  // What the sweep reads.
  const skin::SkinSurface& skin;
  const morse::MorseSmaleComplex& ms;
  const SweepOptions& opt;
  const skin::RunContext run;  ///< C and Q, the progress reports
  const Vec3 e;                ///< unit height direction (§3.1)

  // The partial mesh and its per-vertex data.
  SurfaceMesh mesh;
  geometry::VertexProperty<Vec3> normal;  ///< unit outward skin normal (dropped with the sweep)
  geometry::VertexProperty<double> rho;   ///< local length scale (Å) (dropped with the sweep)
  geometry::VertexProperty<Index> cell;   ///< mixed cell
  geometry::VertexProperty<VState> state;
  geometry::VertexProperty<Index> held_by;            ///< the critical point holding a Held vertex
  geometry::VertexProperty<std::uint32_t> stamp;      ///< queue stamp (lazy deletion)
  geometry::VertexProperty<std::uint8_t> deferrals;   ///< creeps postponed at the vertex
  geometry::VertexProperty<std::uint8_t> reopenings;  ///< re-opened regions whose rim held the vertex
  geometry::VertexProperty<std::uint8_t> departures;  ///< departures of the vertex (max_departures)

  // The departure queue, the wings to try, the holds.
  std::priority_queue<QueueEntry, std::vector<QueueEntry>, std::greater<>> queue;
  std::vector<Vertex> wing_worklist;
  /// Scratch lists of creep() (the fan) and try_contact() (the vertices a
  /// few hops along the front), kept to reuse their memory; neither call
  /// re-enters itself.
  std::vector<Vertex> scratch_fan, scratch_near_hops;
  std::vector<char> resolved;             ///< saddle bridged or released (holds no more)
  std::vector<std::vector<Vertex>> held;  ///< vertices held per critical point

  // Grids that keep the queries local: one level per octave of rho, so that
  // a query reads points of its own scale only (local_scales() bounds it).
  std::unique_ptr<geometry::LeveledPointGrid> hold_grid;  ///< live saddles and maxima, by their rho
  std::vector<Vec3> critical_positions;                   ///< positions of the critical points (hold_grid's)
  /// Every vertex, for the fan-collision net: ids only (the sweep keeps it to
  /// the end, one entry or two per vertex; papers/decompose/history.md,
  /// "The sweep's grids in one pool").
  std::unique_ptr<geometry::LeveledIndexGrid> vertex_grid;
  /// The vertices whose state is not Interior (the front, free or held): the
  /// contact search reads only these (set_state keeps it).
  std::unique_ptr<geometry::LeveledPointGrid> front_grid;
  double max_hold_radius = 0;
  /// The largest protecting radius over rho of a critical point
  /// (morse::MorseSmaleOptions::protect_factor).
  double protect_factor = 0;
  /// The hold query's reach over the querying vertex's rho, (f + c_r) / (1 - f)
  /// (0 if f >= 1: then every critical point is in every level).
  double hold_reach = 0;
  /// The fan-collision query's reach over rho(v), (1 + collision_radius) c_r.
  double collision_reach = 0;

  // Counters, limits and progress.
  long steps = 0;               ///< departures so far (for max_steps)
  std::size_t fold_checks = 0;  ///< creep()'s fold checks so far (SweepOptions::injected_folds)
  std::size_t seal_holes = 0;   ///< holes met by the seal so far (SweepOptions::force_patch_every)
  double h_min = 0, h_max = 0;  ///< height range of the critical points (progress)
  double next_progress = 0;     ///< next fraction to report
  const bool tracing = static_cast<bool>(opt.trace);
  std::size_t vertex_budget = 0;                                  ///< runaway guard (new_vertex)
  double base_vertex_budget = 0;                                  ///< the budget at the atoms' scale
  double rho_max = 0;                                             ///< largest sphere radius sqrt(w/2) (Å)
  double rho_min_seen = std::numeric_limits<double>::infinity();  ///< smallest rho of a vertex so far (Å)
  SweepStats stats;

  /// The part of the skin this sweep meshes (front/region.h): the whole skin
  /// unless the sweep was handed a region.
  SweptRegion region;

  /// Sets v's state, and keeps front_grid to the vertices not Interior.
  void set_state(Vertex v, VState s) {
    if ((s == VState::Interior) != (state[v] == VState::Interior)) {
      if (s == VState::Interior)
        front_grid->erase(v.idx());
      else
        front_grid->insert(v.idx(), mesh.position(v), rho[v]);
    }
    state[v] = s;
  }
  /// The height e·x of v (Å).
  double height(Vertex v) const { return e.dot(mesh.position(v)); }
  /// The critical point holding x, or kInvalidIndex (x free, interior, or
  /// stuck: held by no critical point).
  Index holder_of(Vertex x) const { return state[x] == VState::Held ? held_by[x] : kInvalidIndex; }
  /// The range [lo, hi] (Å) of rho at the skin points within distance `reach`
  /// of a skin point of local length scale `rho`: rho is 1-Lipschitz
  /// (papers/skin/skin_math.md §4.3), so |rho(x) - rho| <= |x - q|; padded by
  /// a relative 1e-9 for rounding. The scale range of the grids' queries.
  static std::pair<double, double> local_scales(double rho, double reach) {
    const double slack = 1e-9 * (rho + reach);
    return {rho - reach - slack, rho + reach + slack};
  }
  /// The live saddles and maxima c whose protecting sphere comes within `r`
  /// of the skin point p of local length scale `rho_p` (|p - c| < r_p(c) + r),
  /// r its disc radius: calls fn(c, position) for a superset of them. With
  /// r_p = f rho(c) and rho 1-Lipschitz, |p - c| < (f rho_p + r) / (1 - f) and
  /// |rho(c) - rho_p| <= |p - c| for them.
  template <class Fn>
  void for_each_hold_near(const Vec3& p, double rho_p, double r, Fn&& fn) const {
    // r = disc_factor · rho_p here, so the reach is hold_reach · rho_p.
    const double reach = hold_reach > 0 && hold_reach < 1
                             ? (protect_factor * rho_p + r) / (1 - protect_factor) * (1 + 1e-9)
                             : max_hold_radius + r;
    hold_grid->for_each_near_at(p, std::min(reach, max_hold_radius + r), rho_p, critical_positions, fn);
  }
  /// The tangent-disc radius r = disc_factor · rho at v (Å), Figure 6.
  double disc_radius(Vertex v) const { return opt.disc_factor * rho[v]; }
  Face add_triangle(Vertex a, Vertex b, Vertex c) { return mesh.add_triangle(a, b, c); }
  /// Tells opt.observer (if any) that `op` ran at departure vertex v (or
  /// invalid) for critical point c (or kInvalidIndex), adding the faces from
  /// first_face on.
  void notify(SweepOperation op, Vertex v, Index c, std::size_t first_face) const {
    if (opt.observer) opt.observer(SweepEvent{op, v, c, first_face, mesh, stats});
  }
  /// printf-style line to opt.trace.
  template <class... Args>
  void tracef(const char* fmt, Args... args) const {
    char buf[512];
    std::snprintf(buf, sizeof buf, fmt, args...);
    std::string line(buf);
    if (!line.empty() && line.back() == '\n') line.pop_back();
    opt.trace(line);
  }
};

}  // namespace skinmesh::front::detail

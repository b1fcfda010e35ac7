// verify/skin_mesh_check.cpp: the skin-aware mesh verifier.
#include "verify/skin_mesh_check.h"

#include <algorithm>
#include <cmath>
#include <future>
#include <numeric>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/parallel.h"
#include "geometry/triangulation/point_grid.h"
#include "skin/restricted_delaunay.h"

namespace skinmesh::verify {

namespace {

/// Length scale (Å) up to which the vertex-distance tolerance is absolute;
/// above it the tolerance grows with the skin's size (its coordinates' rounding
/// does). [derived] the size of a large protein's skin.
constexpr double kAbsoluteToleranceScale = 100.0;
/// Smallest cell of the vertex grid of the restricted Delaunay test (Å): a
/// guard for meshes without edges. [derived] far below any edge.
constexpr double kMinGridCell = 1e-9;
/// A surface Delaunay ball is shrunk by this relative amount before the test
/// for vertices inside it, so that the triangle's own corners and cocircular
/// vertices (on its sphere up to rounding) do not count. [derived] above the
/// rounding of the ball's centre and radius.
constexpr double kBallShrink = 1e-9;
/// Violating triangles listed in the report (the count is complete). [chosen]
constexpr std::size_t kMaxExamples = 16;

/// Frees v's memory (clear() keeps the capacity).
template <class T>
void release(std::vector<T>& v) {
  std::vector<T>().swap(v);
}

/// A number for a message: 17 significant digits, "inf"/"nan" as such.
std::string number_text(double x) {
  std::ostringstream os;
  os.precision(17);
  os << x;
  return os.str();
}

/// "[a, b, c]" for a message.
std::string list_text(const std::vector<std::int64_t>& v) {
  std::ostringstream os;
  os << "[";
  for (std::size_t i = 0; i < v.size(); ++i) os << (i ? ", " : "") << v[i];
  os << "]";
  return os.str();
}

/// A finite number, or null.
nlohmann::ordered_json finite_or_null(double x) {
  return std::isfinite(x) ? nlohmann::ordered_json(x) : nlohmann::ordered_json(nullptr);
}

/// The number of distinct undirected edges {u, w} of the triangles accepted by
/// `valid` that violate [L], rho(v) giving rho at vertex v. `start` holds, at
/// start[v + 1], how many triangle edges have v as their lower vertex; it
/// becomes the offsets of a compressed list of the higher ends, which is
/// sorted per vertex to visit each edge once. The list is made for a run of
/// lower vertices at a time (one pass over the triangles per run), so that
/// it holds about kEntriesPerPass ends, or a kMaxPasses-th of them if that is
/// more (the passes' cost stays a few scans of the triangles at every size):
/// it runs beside the mesh-only checks, at the check's peak.
/// skin::satisfies_L() is symmetric in its two ends, so the order of u, w is
/// irrelevant.
template <class Valid, class Rho>
std::size_t count_L_violations(const geometry::IndexedMesh& mesh, Valid&& valid, std::vector<Index>& start, Rho&& rho,
                               const skin::SizeConstants& size) {
  const auto& P = mesh.positions;
  const std::size_t nv = P.size();
  constexpr std::size_t kEntriesPerPass = std::size_t{1} << 18;  // [chosen] 1 MB of ends at a time
  constexpr std::size_t kMaxPasses = 8;                          // [chosen]
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  const std::size_t per_pass = std::max(kEntriesPerPass, std::size_t(start[nv]) / kMaxPasses + 1);
  std::vector<Index> higher, cursor;
  std::size_t violations = 0;
  for (std::size_t v0 = 0; v0 < nv;) {
    std::size_t v1 = v0 + 1;  // this pass: lower vertices v0 .. v1 - 1
    while (v1 < nv && start[v1 + 1] - start[v0] <= per_pass) ++v1;
    const Index base = start[v0];
    higher.resize(start[v1] - base);
    cursor.assign(start.begin() + std::ptrdiff_t(v0), start.begin() + std::ptrdiff_t(v1));
    for (const auto& t : mesh.triangles) {
      if (!valid(t)) continue;
      for (int i = 0; i < 3; ++i) {
        const Index u = t[i], w = t[(i + 1) % 3], lo = std::min(u, w);
        if (lo >= v0 && lo < v1) higher[cursor[lo - v0]++ - base] = std::max(u, w);
      }
    }
    for (std::size_t v = v0; v < v1; ++v) {
      const auto b = higher.begin() + (start[v] - base), e = higher.begin() + (start[v + 1] - base);
      std::sort(b, e);
      for (auto it = b; it != e; ++it)
        if ((it == b || *it != it[-1]) && !skin::satisfies_L(P[v], P[*it], rho(Index(v)), rho(*it), size)) ++violations;
    }
    v0 = v1;
  }
  return violations;
}

}  // namespace

std::string SkinCheckReport::to_json() const {
  nlohmann::ordered_json j;
  j["ok"] = ok();
  j["closed"] = mesh.closed;
  j["manifold"] = mesh.edge_manifold && mesh.vertex_manifold;
  j["oriented"] = mesh.oriented;
  j["outward"] = num_inward_triangles == 0;
  j["num_inward_triangles"] = num_inward_triangles;
  j["self_intersections"] = mesh.self_intersections_checked ? nlohmann::ordered_json(mesh.num_self_intersections)
                                                            : nlohmann::ordered_json(nullptr);
  j["component_euler"] = component_euler;
  j["expected_component_euler"] = expected_component_euler;
  j["expected_components"] = expected.components();
  j["expected_euler"] = expected.euler_skin();
  j["topology_matches"] = topology_matches;
  j["max_vertex_distance"] = finite_or_null(max_vertex_distance);
  j["num_far_vertices"] = num_far_vertices;
  j["vertex_distance_tolerance"] = finite_or_null(vertex_distance_tolerance);
  j["min_angle_deg"] = finite_or_null(mesh.min_angle_deg);
  j["max_angle_deg"] = finite_or_null(mesh.max_angle_deg);
  j["min_angle_required_deg"] = finite_or_null(min_angle_required_deg);
  j["angle_histogram_10deg"] = mesh.angle_histogram;
  j["num_L_violations"] =
      size_conditions_checked ? nlohmann::ordered_json(num_L_violations) : nlohmann::ordered_json(nullptr);
  j["num_U_violations"] =
      size_conditions_checked ? nlohmann::ordered_json(num_U_violations) : nlohmann::ordered_json(nullptr);
  j["num_rdt_violations"] =
      restricted_delaunay_checked ? nlohmann::ordered_json(num_rdt_violations) : nlohmann::ordered_json(nullptr);
  j["problems"] = problems;
  j["mesh"] = nlohmann::ordered_json::parse(mesh.to_json());
  return j.dump(2) + "\n";
}

SkinCheckReport check_skin_mesh(const skin::SkinSurface& skin, const geometry::IndexedMesh& mesh,
                                const SkinCheckOptions& opt, const skin::RunContext& run) {
  SkinCheckReport rep;
  geometry::MeshCheckOptions mopt;
  mopt.check_self_intersections = opt.check_self_intersections;
  mopt.small_angle_threshold_deg = opt.min_angle_deg;
  // The mesh-only checks share nothing with the skin checks below but the
  // (read-only) mesh: with two threads they run beside them.
  const int threads = thread_count(run.threads);
  mopt.threads = threads;
  std::future<geometry::MeshCheckReport> mesh_report;
  if (threads >= 2)
    mesh_report = std::async(std::launch::async, [&mesh, mopt] { return geometry::check_mesh(mesh, mopt); });
  else
    rep.mesh = geometry::check_mesh(mesh, mopt);
  rep.min_angle_required_deg = opt.min_angle_deg;
  rep.size_conditions_checked = opt.check_size_conditions;
  std::vector<std::string> skin_problems;
  const std::size_t nv = mesh.positions.size();
  const auto& P = mesh.positions;

  // Vertices: distance to the skin, and the cell, from which the tests
  // below take the normal and rho again (32 bytes a vertex not kept beside
  // the mesh-only checks' arrays).
  std::vector<Index> cell(nv, kInvalidIndex);
  // Point location walks from a hint: the caller's cell of the vertex if
  // given, else the cell of a vertex located before that shares a triangle
  // with v (one edge away), else the last cell found. Without the caller's
  // cells, vertices are visited in triangle order so that such a neighbour
  // exists; vertices of no triangle come last. (Hints change only the walk,
  // not the cell's patch at the point: f, grad f and rho are continuous
  // across faces.) The caller's cells matter for memory as well: walks
  // between neighbouring vertices cross about three cells each and make the
  // planes of about a third of the mixed complex (papers/decompose/
  // history.md, "Cells and planes made on first use").
  const bool given_cells = opt.vertex_cells.size() == nv;
  std::vector<Index> order;
  std::vector<Index> order_hint;  // the position in `order` of v's hint vertex, or kInvalidIndex
  if (!given_cells) {
    std::vector<Index> position(nv, kInvalidIndex);
    order.reserve(nv);
    order_hint.reserve(nv);
    for (const auto& t : mesh.triangles) {
      Index from = kInvalidIndex;
      for (int i = 0; i < 3; ++i)
        if (t[i] < nv && position[t[i]] != kInvalidIndex) from = position[t[i]];
      for (int i = 0; i < 3; ++i) {
        const Index v = t[i];
        if (v >= nv || position[v] != kInvalidIndex) continue;
        position[v] = static_cast<Index>(order.size());
        order.push_back(v);
        order_hint.push_back(from);
        from = position[v];
      }
    }
    for (std::size_t v = 0; v < nv; ++v)
      if (position[v] == kInvalidIndex) order.push_back(static_cast<Index>(v)), order_hint.push_back(kInvalidIndex);
  }
  rep.vertex_distance_tolerance =
      opt.max_vertex_distance * std::max(1.0, skin.length_scale() / kAbsoluteToleranceScale);
  // The vertices in blocks of kSampleGrain consecutive ones of `order`, on the
  // threads: a block takes hints only from its own vertices (a walk from
  // another block's cell would race with that block), so the cells found, and
  // every value below, do not depend on the thread count.
  constexpr std::size_t kSampleGrain = 8192;  // [chosen] many walks per block, few cold starts
  struct Farthest {
    double distance = 0;
    Index vertex = kInvalidIndex;
    std::size_t far = 0;  // vertices beyond the tolerance
  };
  const std::size_t num_sample_blocks = (nv + kSampleGrain - 1) / kSampleGrain;
  std::vector<Farthest> farthest(num_sample_blocks);
  parallel_for(num_sample_blocks, threads, 1, [&](std::size_t blk) {
    const std::size_t begin = blk * kSampleGrain, end = std::min(nv, begin + kSampleGrain);
    Farthest& f = farthest[blk];
    Index last = kInvalidIndex;
    for (std::size_t k = begin; k < end; ++k) {
      const Index v = given_cells ? Index(k) : order[k];  // with the caller's cells, in index order
      if (!P[v].allFinite()) continue;
      Index h = last;
      if (given_cells) {
        h = opt.vertex_cells[v] < skin.mixed_complex().num_cells() ? opt.vertex_cells[v] : last;
      } else {
        const Index from = order_hint[k];
        if (from != kInvalidIndex && from >= begin && cell[order[from]] != kInvalidIndex) h = cell[order[from]];
      }
      const skin::SkinSample s = skin.sample(P[v], h);
      last = cell[v] = s.cell;
      const double g = s.gradient.norm();
      const double d = std::abs(s.f) / g;
      if (d > f.distance) f.distance = d, f.vertex = v;
      if (d > rep.vertex_distance_tolerance) ++f.far;
    }
  });
  for (const Farthest& f : farthest) {  // in block order: the first farthest vertex, as one loop finds it
    if (f.distance > rep.max_vertex_distance) rep.max_vertex_distance = f.distance, rep.worst_vertex = f.vertex;
    rep.num_far_vertices += f.far;
  }
  release(order);
  release(order_hint);
  if (rep.num_far_vertices)
    skin_problems.push_back(std::to_string(rep.num_far_vertices) + " vertices farther than " +
                            number_text(rep.vertex_distance_tolerance) + " Å from the skin (max " +
                            number_text(rep.max_vertex_distance) + " Å)");

  // Triangles: orientation against the skin normal, [U]; edges: [L].
  auto valid = [&](const std::array<Index, 3>& t) {
    return t[0] < nv && t[1] < nv && t[2] < nv && t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
  };
  std::vector<Index> edge_start(nv + 1, 0);  // edges listed at their lower vertex (CSR)
  const skin::MixedComplex& mc = skin.mixed_complex();
  auto normal = [&](Index v) -> Vec3 {  // the sample's gradient over its norm
    if (cell[v] == kInvalidIndex) return Vec3::Zero();
    const Vec3 g = mc.gradient(cell[v], P[v]);
    return g / g.norm();
  };
  auto rho = [&](Index v) { return cell[v] == kInvalidIndex ? 0.0 : mc.rho(cell[v], P[v]); };  // the sample's rho
  for (const auto& t : mesh.triangles) {
    if (!valid(t)) continue;
    const Vec3 &a = P[t[0]], &b = P[t[1]], &c = P[t[2]];
    if ((b - a).cross(c - a).dot(normal(t[0]) + normal(t[1]) + normal(t[2])) <= 0) ++rep.num_inward_triangles;
    if (opt.check_size_conditions && !skin::satisfies_U(a, b, c, rho(t[0]), rho(t[1]), rho(t[2]), run.size))
      ++rep.num_U_violations;
    for (int i = 0; i < 3; ++i) ++edge_start[std::min(t[i], t[(i + 1) % 3]) + 1];
  }
  // What the tests below do not read goes back as soon as it is read: they
  // run beside the mesh-only checks, at the peak of the whole run's memory.
  if (opt.check_size_conditions) rep.num_L_violations = count_L_violations(mesh, valid, edge_start, rho, run.size);
  release(edge_start);
  if (rep.num_inward_triangles)
    skin_problems.push_back(std::to_string(rep.num_inward_triangles) +
                            " triangles face inwards (against the skin normal)");
  if (rep.num_L_violations) skin_problems.push_back(std::to_string(rep.num_L_violations) + " edges violate [L]");
  if (rep.num_U_violations) skin_problems.push_back(std::to_string(rep.num_U_violations) + " triangles violate [U]");
  const std::size_t min_angle_slot = skin_problems.size();  // the angle message goes here

  // Restricted Delaunay: the surface Delaunay ball of every triangle is empty.
  if (opt.check_restricted_delaunay && !mesh.triangles.empty()) {
    rep.restricted_delaunay_checked = true;
    double mean_edge = 0;
    std::size_t ne = 0;
    for (const auto& t : mesh.triangles)
      if (valid(t)) mean_edge += (P[t[0]] - P[t[1]]).norm(), ++ne;
    mean_edge = ne ? mean_edge / ne : 1.0;
    // Indices only: the mesh's positions stay put while the grid is read, and
    // the grid is built beside the broad phase's boxes, at the check's peak.
    const geometry::FlatIndexGrid grid(P, std::max(mean_edge, kMinGridCell));
    // Triangles in blocks on the threads; counts and examples joined in block
    // order, so the report is the one a single loop gives.
    constexpr std::size_t kTriangleGrain = 16384;  // [chosen]
    const std::size_t nt = mesh.triangles.size();
    struct Violations {
      std::size_t count = 0;
      std::vector<Index> examples;
    };
    std::vector<Violations> found((nt + kTriangleGrain - 1) / kTriangleGrain);
    parallel_for(found.size(), threads, 1, [&](std::size_t blk) {
      Violations& out = found[blk];
      for (std::size_t ti = blk * kTriangleGrain, end = std::min(nt, ti + kTriangleGrain); ti < end; ++ti) {
        const auto& t = mesh.triangles[ti];
        if (!valid(t)) continue;
        Vec3 m;
        Index c = cell[t[0]];
        bool bad = !skin::surface_delaunay_centre(skin, P[t[0]], P[t[1]], P[t[2]], m, c);
        if (!bad) {
          const double r = (m - P[t[0]]).norm() * (1 - kBallShrink);
          bad = grid.any_near(m, r, [&](Index v, const Vec3&) { return v != t[0] && v != t[1] && v != t[2]; });
        }
        if (bad) {
          ++out.count;
          if (out.examples.size() < kMaxExamples) out.examples.push_back(static_cast<Index>(ti));
        }
      }
    });
    for (const Violations& v : found) {
      rep.num_rdt_violations += v.count;
      for (Index ti : v.examples)
        if (rep.rdt_violation_examples.size() < kMaxExamples) rep.rdt_violation_examples.push_back(ti);
    }
    if (rep.num_rdt_violations)
      skin_problems.push_back(std::to_string(rep.num_rdt_violations) +
                              " triangles are not restricted Delaunay (non-empty surface Delaunay ball)");
  }

  // Join the mesh-only checks; problems in the order of the single-thread report.
  if (mesh_report.valid()) rep.mesh = mesh_report.get();
  rep.problems = rep.mesh.problems;
  for (std::size_t i = 0; i <= skin_problems.size(); ++i) {
    if (i == min_angle_slot && rep.mesh.num_triangles > 0 && rep.mesh.min_angle_deg < opt.min_angle_deg)
      rep.problems.push_back("minimum angle " + number_text(rep.mesh.min_angle_deg) + "° below " +
                             number_text(opt.min_angle_deg) + "°");
    if (i < skin_problems.size()) rep.problems.push_back(skin_problems[i]);
  }

  // Topology against K0 (and the caller's per-component expectation).
  rep.expected =
      opt.expected_topology ? *opt.expected_topology : skin::dual_complex_topology(skin.mixed_complex(), threads);
  for (const auto& comp : rep.mesh.components) rep.component_euler.push_back(comp.euler);
  std::sort(rep.component_euler.begin(), rep.component_euler.end());
  rep.expected_component_euler = opt.expected_component_euler;
  if (rep.expected_component_euler.empty()) {
    if (rep.expected.total_genus() == 0)
      rep.expected_component_euler.assign(rep.expected.components(), 2);
    else if (rep.expected.components() == 1)
      rep.expected_component_euler.assign(1, rep.expected.euler_skin());
  }
  std::sort(rep.expected_component_euler.begin(), rep.expected_component_euler.end());
  const std::int64_t total = std::accumulate(rep.component_euler.begin(), rep.component_euler.end(), std::int64_t{0});
  if (opt.shells.selects() && opt.expected_component_euler.empty()) {
    // Some shells only: K0 says how many bodies (betti0) and cavities
    // (betti2) the skin has, not which genus each shell has, so the kept
    // shells' Euler characteristics are bounded by the skin's total genus
    // (exact when that is 0: every shell a sphere).
    rep.expected_component_euler.clear();
    std::int64_t bodies = 0, cavities = 0, genus = 0;
    bool even = true;
    for (const auto& comp : rep.mesh.components) {
      (comp.volume < 0 ? cavities : bodies)++;
      even = even && comp.euler <= 2 && comp.euler % 2 == 0;
      genus += (2 - comp.euler) / 2;
    }
    const std::int64_t want_bodies = opt.shells.cavities == skin::CavityChoice::Only ? 0 : rep.expected.betti0;
    const std::int64_t max_cavities = opt.shells.cavities == skin::CavityChoice::Remove ? 0 : rep.expected.betti2;
    const bool cavities_ok = opt.shells.partial_cavities() ? cavities <= max_cavities : cavities == max_cavities;
    rep.topology_matches = bodies == want_bodies && cavities_ok && even && genus <= rep.expected.total_genus();
    if (!rep.topology_matches)
      rep.problems.push_back("topology: " + std::to_string(bodies) + " bodies and " + std::to_string(cavities) +
                             " cavities of total genus " + std::to_string(genus) + ", expected " +
                             std::to_string(want_bodies) + " bodies and " +
                             (opt.shells.partial_cavities() ? "at most " : "") + std::to_string(max_cavities) +
                             " cavities of total genus at most " + std::to_string(rep.expected.total_genus()) +
                             " (--cavities " + skin::cavity_choice_name(opt.shells.cavities) + ")");
    return rep;
  }
  rep.topology_matches = static_cast<int>(rep.component_euler.size()) == rep.expected.components() &&
                         total == rep.expected.euler_skin() &&
                         (rep.expected_component_euler.empty() || rep.expected_component_euler == rep.component_euler);
  if (!rep.topology_matches) {
    rep.problems.push_back("topology: components' Euler characteristics " + list_text(rep.component_euler) +
                           ", expected " + std::to_string(rep.expected.components()) + " components with total " +
                           std::to_string(rep.expected.euler_skin()) +
                           (rep.expected_component_euler.empty() ? "" : " " + list_text(rep.expected_component_euler)));
  }
  return rep;
}

}  // namespace skinmesh::verify

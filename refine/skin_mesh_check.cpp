// refine/skin_mesh_check.cpp: the skin-aware mesh verifier.
#include "refine/skin_mesh_check.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <unordered_set>

#include "geometry/point_grid.h"
#include "refine/restricted_delaunay.h"

namespace skinmesh::refine {

namespace {

std::string json_number(double x) {
  if (!std::isfinite(x)) return "null";
  std::ostringstream os;
  os.precision(17);
  os << x;
  return os.str();
}

template <class T>
std::string json_array(const std::vector<T>& v) {
  std::ostringstream os;
  os << "[";
  for (std::size_t i = 0; i < v.size(); ++i) os << (i ? ", " : "") << v[i];
  os << "]";
  return os.str();
}

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') out += '\\';
    if (ch == '\n') {
      out += "\\n";
      continue;
    }
    out += ch;
  }
  return out + "\"";
}

}  // namespace

std::string SkinCheckReport::to_json() const {
  std::ostringstream os;
  os << "{\n";
  os << "  \"ok\": " << (ok() ? "true" : "false") << ",\n";
  os << "  \"closed\": " << (mesh.closed ? "true" : "false") << ",\n";
  os << "  \"manifold\": " << (mesh.edge_manifold && mesh.vertex_manifold ? "true" : "false") << ",\n";
  os << "  \"oriented\": " << (mesh.oriented ? "true" : "false") << ",\n";
  os << "  \"outward\": " << (num_inward_triangles == 0 ? "true" : "false") << ",\n";
  os << "  \"num_inward_triangles\": " << num_inward_triangles << ",\n";
  os << "  \"self_intersections\": "
     << (mesh.self_intersections_checked ? std::to_string(mesh.num_self_intersections) : "null") << ",\n";
  os << "  \"component_euler\": " << json_array(component_euler) << ",\n";
  os << "  \"expected_component_euler\": " << json_array(expected_component_euler) << ",\n";
  os << "  \"expected_components\": " << expected.components() << ",\n";
  os << "  \"expected_euler\": " << expected.euler_skin() << ",\n";
  os << "  \"topology_matches\": " << (topology_matches ? "true" : "false") << ",\n";
  os << "  \"max_vertex_distance\": " << json_number(max_vertex_distance) << ",\n";
  os << "  \"num_far_vertices\": " << num_far_vertices << ",\n";
  os << "  \"min_angle_deg\": " << json_number(mesh.min_angle_deg) << ",\n";
  os << "  \"max_angle_deg\": " << json_number(mesh.max_angle_deg) << ",\n";
  os << "  \"min_angle_required_deg\": " << json_number(min_angle_required_deg) << ",\n";
  os << "  \"angle_histogram_10deg\": " << json_array(mesh.angle_histogram) << ",\n";
  os << "  \"num_L_violations\": " << num_L_violations << ",\n";
  os << "  \"num_U_violations\": " << num_U_violations << ",\n";
  os << "  \"num_rdt_violations\": "
     << (restricted_delaunay_checked ? std::to_string(num_rdt_violations) : "null") << ",\n";
  os << "  \"problems\": [";
  for (std::size_t i = 0; i < problems.size(); ++i) os << (i ? ", " : "") << json_string(problems[i]);
  os << "],\n";
  os << "  \"mesh\": " << mesh.to_json() << "\n";
  os << "}\n";
  return os.str();
}

SkinCheckReport check_skin_mesh(const skin::SkinSurface& skin, const geometry::IndexedMesh& mesh,
                                const SkinCheckOptions& opt) {
  SkinCheckReport rep;
  geometry::MeshCheckOptions mopt;
  mopt.check_self_intersections = opt.check_self_intersections;
  mopt.small_angle_threshold_deg = opt.min_angle_deg;
  rep.mesh = geometry::check_mesh(mesh, mopt);
  rep.min_angle_required_deg = opt.min_angle_deg;
  rep.problems = rep.mesh.problems;
  const std::size_t nv = mesh.positions.size();
  const auto& P = mesh.positions;

  // Vertices: distance to the skin, normal, rho.
  std::vector<double> rho(nv, 0.0);
  std::vector<Vec3> normal(nv, Vec3::Zero());
  std::vector<Index> cell(nv, kInvalidIndex);
  Index hint = kInvalidIndex;
  for (std::size_t v = 0; v < nv; ++v) {
    if (!P[v].allFinite()) continue;
    const skin::SkinSample s = skin.sample(P[v], hint);
    hint = cell[v] = s.cell;
    rho[v] = s.rho;
    const double g = s.gradient.norm();
    normal[v] = s.gradient / g;
    const double d = std::abs(s.f) / g;
    if (d > rep.max_vertex_distance) rep.max_vertex_distance = d, rep.worst_vertex = static_cast<Index>(v);
    if (d > opt.max_vertex_distance) ++rep.num_far_vertices;
  }
  if (rep.num_far_vertices)
    rep.problems.push_back(std::to_string(rep.num_far_vertices) + " vertices farther than " +
                           json_number(opt.max_vertex_distance) + " Å from the skin (max " +
                           json_number(rep.max_vertex_distance) + " Å)");

  // Triangles: orientation against the skin normal, [U]; edges: [L].
  auto valid = [&](const std::array<Index, 3>& t) {
    return t[0] < nv && t[1] < nv && t[2] < nv && t[0] != t[1] && t[1] != t[2] && t[0] != t[2];
  };
  std::unordered_set<std::uint64_t> edges;
  edges.reserve(mesh.triangles.size() * 2);
  for (const auto& t : mesh.triangles) {
    if (!valid(t)) continue;
    const Vec3 &a = P[t[0]], &b = P[t[1]], &c = P[t[2]];
    if ((b - a).cross(c - a).dot(normal[t[0]] + normal[t[1]] + normal[t[2]]) <= 0) ++rep.num_inward_triangles;
    if (!satisfies_U(a, b, c, rho[t[0]], rho[t[1]], rho[t[2]], opt.size)) ++rep.num_U_violations;
    for (int i = 0; i < 3; ++i) {
      const Index u = t[i], w = t[(i + 1) % 3];
      const std::uint64_t key = (std::uint64_t(std::min(u, w)) << 32) | std::max(u, w);
      if (edges.insert(key).second && !satisfies_L(P[u], P[w], rho[u], rho[w], opt.size)) ++rep.num_L_violations;
    }
  }
  if (rep.num_inward_triangles)
    rep.problems.push_back(std::to_string(rep.num_inward_triangles) +
                           " triangles face inwards (against the skin normal)");
  if (rep.num_L_violations)
    rep.problems.push_back(std::to_string(rep.num_L_violations) + " edges violate [L]");
  if (rep.num_U_violations)
    rep.problems.push_back(std::to_string(rep.num_U_violations) + " triangles violate [U]");
  if (rep.mesh.num_triangles > 0 && rep.mesh.min_angle_deg < opt.min_angle_deg)
    rep.problems.push_back("minimum angle " + json_number(rep.mesh.min_angle_deg) + "° below " +
                           json_number(opt.min_angle_deg) + "°");

  // Restricted Delaunay: the surface Delaunay ball of every triangle is empty.
  if (opt.check_restricted_delaunay && !mesh.triangles.empty()) {
    rep.restricted_delaunay_checked = true;
    double mean_edge = 0;
    std::size_t ne = 0;
    for (const auto& t : mesh.triangles)
      if (valid(t)) mean_edge += (P[t[0]] - P[t[1]]).norm(), ++ne;
    mean_edge = ne ? mean_edge / ne : 1.0;
    geometry::PointGrid grid(std::max(mean_edge, 1e-9));
    for (std::size_t v = 0; v < nv; ++v)
      if (P[v].allFinite()) grid.insert(static_cast<Index>(v), P[v]);
    for (std::size_t ti = 0; ti < mesh.triangles.size(); ++ti) {
      const auto& t = mesh.triangles[ti];
      if (!valid(t)) continue;
      Vec3 m;
      Index c = cell[t[0]];
      bool bad = !surface_delaunay_centre(skin, P[t[0]], P[t[1]], P[t[2]], m, c);
      if (!bad) {
        const double r = (m - P[t[0]]).norm() * (1 - 1e-9);
        grid.for_each_near(m, r, [&](Index v, const Vec3&) {
          if (v != t[0] && v != t[1] && v != t[2]) bad = true;
        });
      }
      if (bad) {
        ++rep.num_rdt_violations;
        if (rep.rdt_violation_examples.size() < 16) rep.rdt_violation_examples.push_back(static_cast<Index>(ti));
      }
    }
    if (rep.num_rdt_violations)
      rep.problems.push_back(std::to_string(rep.num_rdt_violations) +
                             " triangles are not restricted Delaunay (non-empty surface Delaunay ball)");
  }

  // Topology against K0 (and the caller's per-component expectation).
  rep.expected = skin::dual_complex_topology(skin.mixed_complex());
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
  rep.topology_matches = static_cast<int>(rep.component_euler.size()) == rep.expected.components() &&
                         total == rep.expected.euler_skin() &&
                         (rep.expected_component_euler.empty() ||
                          rep.expected_component_euler == rep.component_euler);
  if (!rep.topology_matches) {
    rep.problems.push_back("topology: components' Euler characteristics " + json_array(rep.component_euler) +
                           ", expected " + std::to_string(rep.expected.components()) +
                           " components with total " + std::to_string(rep.expected.euler_skin()) +
                           (rep.expected_component_euler.empty() ? "" : " " + json_array(rep.expected_component_euler)));
  }
  return rep;
}

}  // namespace skinmesh::refine

// geometry/check/mesh_checks.cpp: check_mesh() (see mesh_checks.h) as a sequence of
// steps — the triangle classes (here), the topology (mesh_checks_topology.cpp),
// volumes, areas and angles (mesh_checks_geometry.cpp), the exact
// self-intersections (mesh_checks_intersections.cpp) — then the list of problems
// and ok(). The JSON report is in mesh_checks_json.cpp.
#include "geometry/check/mesh_checks.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "geometry/check/mesh_checks_internal.h"
#include "geometry/kernel/triangle_intersection.h"

namespace skinmesh::geometry {

namespace {

using mesh_checks_detail::add_example;
using mesh_checks_detail::TriangleClasses;
using mesh_checks_detail::TriangleKind;

bool finite(const Vec3& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

/// The class of every triangle and the state of every vertex (TriangleClasses),
/// and the report's counts of them: num_nonfinite_vertices,
/// num_out_of_range_triangles, num_repeated_index_triangles,
/// num_zero_area_triangles, num_degenerate_triangles, num_unreferenced_vertices
/// and degenerate_triangle_examples (at most `max_examples`). Zero area is
/// decided exactly (is_degenerate_triangle()).
TriangleClasses classify_triangles(const IndexedMesh& mesh, std::size_t max_examples, MeshCheckReport& r) {
  const auto& P = mesh.positions;
  const auto& T = mesh.triangles;
  const std::size_t nv = P.size(), nt = T.size();
  TriangleClasses c;
  c.vertex_finite.resize(nv);
  for (std::size_t v = 0; v < nv; ++v) {
    c.vertex_finite[v] = finite(P[v]);
    if (!c.vertex_finite[v]) ++r.num_nonfinite_vertices;
  }
  c.kind.assign(nt, TriangleKind::kGood);
  c.referenced.assign(nv, false);
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = T[t];
    if (tri[0] >= nv || tri[1] >= nv || tri[2] >= nv) {
      c.kind[t] = TriangleKind::kOutOfRange;
      ++r.num_out_of_range_triangles;
      continue;
    }
    for (Index v : tri) c.referenced[v] = true;
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) {
      c.kind[t] = TriangleKind::kRepeated;
      ++r.num_repeated_index_triangles;
      add_example(r.degenerate_triangle_examples, Index(t), max_examples);
    } else if (!c.vertex_finite[tri[0]] || !c.vertex_finite[tri[1]] || !c.vertex_finite[tri[2]]) {
      c.kind[t] = TriangleKind::kNonFinite;
    } else if (is_degenerate_triangle(P[tri[0]], P[tri[1]], P[tri[2]])) {
      c.kind[t] = TriangleKind::kZeroArea;
      ++r.num_zero_area_triangles;
      add_example(r.degenerate_triangle_examples, Index(t), max_examples);
    }
  }
  r.num_degenerate_triangles = r.num_repeated_index_triangles + r.num_zero_area_triangles;
  r.num_unreferenced_vertices = std::size_t(std::count(c.referenced.begin(), c.referenced.end(), false));
  return c;
}

/// MeshCheckReport::problems from the counts of `r`: one line "<count> <what>"
/// per kind of problem that occurs, in a fixed order.
void list_problems(MeshCheckReport& r) {
  auto add = [&](std::size_t n, const std::string& what) {
    if (n > 0) r.problems.push_back(std::to_string(n) + " " + what);
  };
  add(r.num_out_of_range_triangles, "triangles with a vertex index out of range");
  add(r.num_nonfinite_vertices, "vertices with a non-finite coordinate");
  add(r.num_repeated_index_triangles, "triangles with a repeated vertex index");
  add(r.num_zero_area_triangles, "zero-area (collinear) triangles");
  add(r.num_duplicate_triangles, "duplicate triangles");
  add(r.num_boundary_edges, "boundary edges (the mesh is not closed)");
  add(r.num_nonmanifold_edges, "non-manifold edges (more than two triangles)");
  add(r.num_nonmanifold_vertices, "non-manifold vertices (triangles not a single fan)");
  add(r.num_misoriented_edges, "edges used twice in the same direction (inconsistent orientation)");
  add(r.num_self_intersections, "pairs of self-intersecting triangles");
}

}  // namespace

// ---------------------------------------------------------------------------
// check_mesh
// ---------------------------------------------------------------------------

MeshCheckReport check_mesh(const IndexedMesh& mesh, const MeshCheckOptions& options) {
  MeshCheckReport r;
  r.num_vertices = mesh.positions.size();
  r.num_triangles = mesh.triangles.size();
  r.small_angle_threshold_deg = options.small_angle_threshold_deg;
  const TriangleClasses classes = classify_triangles(mesh, options.max_examples, r);
  auto incidence =
      std::make_unique<mesh_checks_detail::VertexIncidence>(mesh_checks_detail::build_incidence(mesh, classes));
  std::vector<Index> component = mesh_checks_detail::check_topology(mesh, classes, *incidence, options.max_examples, r);
  mesh_checks_detail::measure_components(mesh, classes, component, r);
  std::vector<Index>().swap(component);  // freed before the self-intersection search, the peak
  mesh_checks_detail::measure_angles(mesh, classes, options.small_angle_threshold_deg, r);
  if (options.check_self_intersections) {
    // The simple fans are all the search needs of the incidence: it goes back
    // before the boxes are made (12 bytes per triangle at the check's peak).
    const std::vector<std::uint8_t> fan_ok =
        mesh_checks_detail::simple_fan_vertices(mesh, classes, *incidence, options.threads);
    incidence.reset();
    mesh_checks_detail::find_self_intersections(mesh, classes, fan_ok, options.max_examples, options.threads, r);
  }
  list_problems(r);
  return r;
}

bool MeshCheckReport::ok() const {
  return num_out_of_range_triangles == 0 && num_nonfinite_vertices == 0 && num_degenerate_triangles == 0 &&
         num_duplicate_triangles == 0 && closed && edge_manifold && vertex_manifold && oriented &&
         num_self_intersections == 0;
}

}  // namespace skinmesh::geometry

// geometry/check/mesh_checks_json.cpp: MeshCheckReport::to_json() (see mesh_checks.h),
// written with nlohmann-json (compact, keys in the order of the report).
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "geometry/check/mesh_checks.h"
#include "geometry/check/mesh_checks_internal.h"

namespace skinmesh::geometry {

namespace {

using Json = nlohmann::ordered_json;

/// A finite number, or null (JSON has no infinity or NaN).
Json finite_or_null(double x) { return std::isfinite(x) ? Json(x) : Json(nullptr); }

/// A vertex or triangle index, or null for kInvalidIndex.
Json index_or_null(Index x) { return x == kInvalidIndex ? Json(nullptr) : Json(std::uint64_t(x)); }

Json indices(const std::vector<Index>& xs) {
  Json a = Json::array();
  for (Index x : xs) a.push_back(index_or_null(x));
  return a;
}

Json pairs(const std::vector<std::array<Index, 2>>& xs) {
  Json a = Json::array();
  for (const auto& p : xs) a.push_back(Json::array({index_or_null(p[0]), index_or_null(p[1])}));
  return a;
}

}  // namespace

std::string MeshCheckReport::to_json() const {
  Json j;
  j["ok"] = ok();
  j["num_vertices"] = num_vertices;
  j["num_triangles"] = num_triangles;
  j["num_unreferenced_vertices"] = num_unreferenced_vertices;
  j["num_nonfinite_vertices"] = num_nonfinite_vertices;
  j["num_edges"] = num_edges;
  j["num_out_of_range_triangles"] = num_out_of_range_triangles;
  j["num_repeated_index_triangles"] = num_repeated_index_triangles;
  j["num_zero_area_triangles"] = num_zero_area_triangles;
  j["num_degenerate_triangles"] = num_degenerate_triangles;
  j["num_duplicate_triangles"] = num_duplicate_triangles;
  j["degenerate_triangle_examples"] = indices(degenerate_triangle_examples);
  j["num_boundary_edges"] = num_boundary_edges;
  j["num_nonmanifold_edges"] = num_nonmanifold_edges;
  j["num_misoriented_edges"] = num_misoriented_edges;
  j["num_nonmanifold_vertices"] = num_nonmanifold_vertices;
  j["closed"] = closed;
  j["edge_manifold"] = edge_manifold;
  j["vertex_manifold"] = vertex_manifold;
  j["oriented"] = oriented;
  j["boundary_edge_examples"] = pairs(boundary_edge_examples);
  j["nonmanifold_edge_examples"] = pairs(nonmanifold_edge_examples);
  j["misoriented_edge_examples"] = pairs(misoriented_edge_examples);
  j["nonmanifold_vertex_examples"] = indices(nonmanifold_vertex_examples);
  Json comps = Json::array();
  for (const MeshComponent& c : components) {
    Json o;
    o["vertices"] = c.vertices;
    o["edges"] = c.edges;
    o["faces"] = c.faces;
    o["euler"] = std::int64_t(c.euler);
    o["closed"] = c.closed;
    o["manifold"] = c.manifold;
    o["oriented"] = c.oriented;
    o["genus"] = c.genus ? Json(std::int64_t(*c.genus)) : Json(nullptr);
    o["volume"] = finite_or_null(c.volume);
    o["area"] = finite_or_null(c.area);
    comps.push_back(std::move(o));
  }
  j["components"] = std::move(comps);
  j["num_vertex_components"] = num_vertex_components;
  j["self_intersections_checked"] = self_intersections_checked;
  j["num_self_intersections"] = num_self_intersections;
  j["self_intersection_examples"] = pairs(self_intersection_examples);
  j["num_pairs_tested"] = num_pairs_tested;
  j["min_angle_deg"] = finite_or_null(min_angle_deg);
  j["max_angle_deg"] = finite_or_null(max_angle_deg);
  j["worst_triangle"] = index_or_null(worst_triangle);
  j["angle_histogram"] = angle_histogram;
  j["angle_histogram_bin_deg"] = mesh_checks_detail::kHistogramBinDeg;
  j["small_angle_threshold_deg"] = finite_or_null(small_angle_threshold_deg);
  j["num_small_angle_triangles"] = num_small_angle_triangles;
  j["problems"] = problems;
  return j.dump();
}

}  // namespace skinmesh::geometry

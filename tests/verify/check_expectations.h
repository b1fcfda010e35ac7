// tests/verify/check_expectations.h: the assertions shared by the tests that
// verify a finished skin mesh (refine, front): the embedded-surface properties
// of any closed mesh of the skin, and with them the quality properties of
// [L], [U], the restricted Delaunay triangulation and the 21.5° angle bound.
#pragma once

#include <doctest/doctest.h>

#include "verify/skin_mesh_check.h"

namespace skinmesh::test {

/// Closed, manifold, oriented outwards, embedded, on the skin (1e-9 Å up to
/// L = 100 Å, 1e-11 L beyond: verify::SkinCheckOptions::max_vertex_distance), of
/// the expected topology.
inline void check_embedded_skin_mesh(const verify::SkinCheckReport& rep) {
  INFO(rep.to_json());
  CHECK(rep.mesh.closed);
  CHECK(rep.mesh.edge_manifold);
  CHECK(rep.mesh.vertex_manifold);
  CHECK(rep.mesh.oriented);
  CHECK(rep.num_inward_triangles == 0);
  CHECK(rep.mesh.num_self_intersections == 0);
  CHECK(rep.max_vertex_distance <= rep.vertex_distance_tolerance);
  CHECK(rep.vertex_distance_tolerance <= 1e-8);  // every test input is smaller than 1000 Å
  CHECK(rep.topology_matches);
}

/// check_embedded_skin_mesh() plus no [L] / [U] / restricted-Delaunay
/// violation, every angle at least 21.5°, and the report's overall verdict.
inline void check_every_property(const verify::SkinCheckReport& rep) {
  check_embedded_skin_mesh(rep);
  INFO(rep.to_json());
  CHECK(rep.num_L_violations == 0);
  CHECK(rep.num_U_violations == 0);
  CHECK(rep.num_rdt_violations == 0);
  CHECK(rep.mesh.min_angle_deg >= 21.5);
  CHECK(rep.ok());
}

}  // namespace skinmesh::test

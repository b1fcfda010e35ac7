// tests/refine/angle_improvement_test.cpp: the angle-improvement pass on
// refined meshes of a one-atom skin (a sphere) and of a two-atom skin (two
// spheres joined by a hyperboloid neck): the smallest angle rises, the
// connectivity is unchanged, and afterwards every property the refinement
// established still holds — checked by the verifier and again by brute force
// over all pairs (every vertex against every surface Delaunay ball, every
// triangle against every triangle, [L] and [U] with rho sampled afresh).
#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include "geometry/check/mesh_checks.h"
#include "refine/angle_improvement.h"
#include "refine/local_refinement.h"
#include "skin/restricted_delaunay.h"
#include "skin/size_conditions.h"
#include "skin/vertex_data.h"
#include "tests/geometry/test_meshes.h"
#include "tests/verify/check_expectations.h"
#include "verify/skin_mesh_check.h"

using namespace skinmesh;

namespace {

constexpr double kDeg = 180.0 / std::numbers::pi;

/// The skin of one atom: the sphere of radius 2 about the origin.
skin::SkinSurface one_atom() { return skin::SkinSurface({{Vec3(0, 0, 0), 2 * 2.0 * 2.0}}); }

/// The skin of two atoms of radius 1.5 whose centres are 1.6 Å apart: two
/// sphere caps and a hyperboloid neck, star-shaped about the origin.
skin::SkinSurface two_atoms() {
  return skin::SkinSurface({{Vec3(-0.8, 0, 0), 2 * 1.5 * 1.5}, {Vec3(0.8, 0, 0), 2 * 1.5 * 1.5}});
}

/// An icosphere of `levels` subdivisions, each vertex moved by up to
/// `jitter` (times its norm) in its tangent plane (seed `seed`), then put on
/// the skin along the ray from the origin; refined by refine_mesh() to [L],
/// [U] and the restricted Delaunay property. With 3 levels and a jitter of
/// 0.05 the refined meshes have smallest angles of 22.9°–25.2° (below the
/// pass's default target of 28°).
geometry::SurfaceMesh refined_mesh(const skin::SkinSurface& skin, int levels, double jitter, unsigned seed) {
  geometry::IndexedMesh m = test::sphere(levels);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  INFO("seed " << seed);
  for (Vec3& p : m.positions) {
    const Vec3 t1 = p.unitOrthogonal(), t2 = p.cross(t1);
    const Vec3 d = (p + jitter * (u(rng) * t1 + u(rng) * t2)).normalized();
    // Start near the skin (radius 1.5–2.3 Å here) and walk along the ray.
    Vec3 out;
    Index cell = kInvalidIndex;
    REQUIRE(skin.project_along_line(1.9 * d, d, 1.0, out, cell));
    p = out;
  }
  geometry::SurfaceMesh mesh = geometry::SurfaceMesh::from_indexed_mesh(m);
  const refine::RefineStats st = refine::refine_mesh(skin, mesh);
  REQUIRE(st.L_left == 0);
  REQUIRE(st.U_left == 0);
  return mesh;
}

/// The vertex triples of the faces, in face order (the connectivity).
std::vector<std::array<Index, 3>> faces_of(const geometry::SurfaceMesh& mesh) {
  std::vector<std::array<Index, 3>> out;
  for (geometry::Face f : mesh.faces()) {
    std::array<Index, 3> t{};
    int i = 0;
    for (geometry::Vertex v : mesh.vertices(f)) t[i++] = v.idx();
    out.push_back(t);
  }
  return out;
}

double min_angle_deg(const geometry::SurfaceMesh& mesh) {
  double q = 1e300;
  for (geometry::Face f : mesh.faces()) {
    Vec3 p[3];
    int i = 0;
    for (geometry::Vertex v : mesh.vertices(f)) p[i++] = mesh.position(v);
    q = std::min(q, geometry::min_angle(p[0], p[1], p[2]) * kDeg);
  }
  return q;
}

/// Brute force over all pairs: every property the pass must keep, computed
/// from scratch (rho and normals sampled afresh, every vertex tested against
/// every triangle's surface Delaunay ball with the verifier's tolerance,
/// every pair of triangles tested for intersection).
void check_by_brute_force(const skin::SkinSurface& skin, const geometry::SurfaceMesh& mesh,
                          const skin::SizeConstants& size) {
  const auto cell = mesh.get_vertex_property(skin::kVertexCell);
  REQUIRE(cell);
  const skin::VertexNormals normal(skin.mixed_complex(), mesh);
  const skin::VertexRhos rho(skin.mixed_complex(), mesh);
  std::vector<geometry::Vertex> verts;
  for (geometry::Vertex v : mesh.vertices()) {
    verts.push_back(v);
    const Vec3& p = mesh.position(v);
    const skin::SkinSample s = skin.sample(p);
    CHECK(std::abs(s.f) / s.gradient.norm() <= 1e-9);  // on the skin
    // The pass keeps the vertices' cells up to date, and with them the
    // normal and rho derived from them.
    CHECK(std::abs(rho[v] - s.rho) <= 1e-9 * s.rho);
    CHECK((normal[v] - s.gradient.normalized()).norm() <= 1e-9);
    CHECK(std::abs(skin.sample(p, cell[v]).f) / s.gradient.norm() <= 1e-9);
  }
  std::size_t L_bad = 0, U_bad = 0, inward = 0, rdt_bad = 0;
  for (geometry::Edge e : mesh.edges()) {
    const geometry::Vertex a = mesh.vertex(e, 0), b = mesh.vertex(e, 1);
    const double ra = skin.sample(mesh.position(a)).rho, rb = skin.sample(mesh.position(b)).rho;
    L_bad += !skin::satisfies_L(mesh.position(a), mesh.position(b), ra, rb, size);
  }
  for (geometry::Face f : mesh.faces()) {
    geometry::Vertex x[3];
    int i = 0;
    for (geometry::Vertex v : mesh.vertices(f)) x[i++] = v;
    const Vec3 &a = mesh.position(x[0]), &b = mesh.position(x[1]), &c = mesh.position(x[2]);
    const double r0 = skin.sample(a).rho, r1 = skin.sample(b).rho, r2 = skin.sample(c).rho;
    U_bad += !skin::satisfies_U(a, b, c, r0, r1, r2, size);
    const Vec3 nt = (b - a).cross(c - a);
    for (const Vec3* p : {&a, &b, &c}) inward += !(nt.dot(skin.normal(*p)) > 0);
    Vec3 m;
    Index hint = kInvalidIndex;
    if (!skin::surface_delaunay_centre(skin, a, b, c, m, hint)) {
      ++rdt_bad;
      continue;
    }
    const double r = (m - a).norm() * (1 - 1e-9);
    for (geometry::Vertex v : verts)
      if (v != x[0] && v != x[1] && v != x[2] && (mesh.position(v) - m).norm() < r) {
        ++rdt_bad;
        break;
      }
  }
  CHECK(L_bad == 0);
  CHECK(U_bad == 0);
  CHECK(inward == 0);
  CHECK(rdt_bad == 0);
  geometry::SurfaceMesh copy = mesh;
  copy.garbage_collection();
  CHECK(test::brute_force_intersections(copy.to_indexed_mesh()).empty());
}

/// Runs the pass on a copy of `mesh` and checks what it must do.
refine::AngleImprovementStats improve_and_check(const skin::SkinSurface& skin, geometry::SurfaceMesh& mesh,
                                                const refine::AngleImprovementOptions& opt = {}) {
  const auto faces_before = faces_of(mesh);
  const double before = min_angle_deg(mesh);
  // The size bound of the neighbourhoods: the largest circumradius / rho_min
  // over the triangles before the pass, by brute force.
  const skin::SizeConstants size;  // improve_angles', from the default run context
  double kappa = size.C * size.Q;
  {
    const skin::VertexRhos rho(skin.mixed_complex(), mesh);
    for (geometry::Face f : mesh.faces()) {
      Vec3 x[3];
      double rho_min = std::numeric_limits<double>::infinity();
      int i = 0;
      for (geometry::Vertex v : mesh.vertices(f)) x[i++] = mesh.position(v), rho_min = std::min(rho_min, rho[v]);
      const double a = (x[1] - x[2]).norm(), b = (x[2] - x[0]).norm(), c = (x[0] - x[1]).norm();
      const double R = a * b * c / (2 * (x[1] - x[0]).cross(x[2] - x[0]).norm());
      kappa = std::max(kappa, R / rho_min);
    }
  }
  {
    geometry::SurfaceMesh copy = mesh;
    copy.garbage_collection();
    test::check_every_property(verify::check_skin_mesh(skin, copy.to_indexed_mesh()));  // a valid start
  }
  const refine::AngleImprovementStats st = refine::improve_angles(skin, mesh, opt);
  const double after = min_angle_deg(mesh);
  INFO("min angle " << before << "° -> " << after << "°, moves " << st.moves << ", refused " << st.refused);
  CHECK(faces_of(mesh) == faces_before);  // no connectivity change
  CHECK(st.min_angle_before_deg == doctest::Approx(before).epsilon(1e-12));
  CHECK(st.min_angle_after_deg == doctest::Approx(after).epsilon(1e-12));
  CHECK(after >= before);
  CHECK(st.kappa >= kappa);
  CHECK(st.kappa == doctest::Approx(kappa).epsilon(1e-5));
  check_by_brute_force(skin, mesh, size);
  geometry::SurfaceMesh copy = mesh;
  copy.garbage_collection();
  test::check_every_property(verify::check_skin_mesh(skin, copy.to_indexed_mesh()));
  return st;
}

}  // namespace

TEST_SUITE("refine") {

TEST_CASE(
    "angle improvement: one sphere, and two atoms (sphere caps and a hyperboloid neck), get larger "
    "angles and keep [L], [U], RDT, embedding") {
  const std::pair<const char*, skin::SkinSurface> skins[] = {{"one atom", one_atom()}, {"two atoms", two_atoms()}};
  for (const auto& [name, skin] : skins) {
    for (unsigned seed : {1u, 2u, 3u}) {
      INFO(name << ", seed " << seed);
      geometry::SurfaceMesh mesh = refined_mesh(skin, 3, 0.05, seed);
      const double before = min_angle_deg(mesh);
      REQUIRE(before < 28.0);  // something to improve (the default target)
      const auto st = improve_and_check(skin, mesh);
      CHECK(st.moves > 0);
      CHECK(min_angle_deg(mesh) > before);
      CHECK(!st.skipped);
    }
  }
}

TEST_CASE("angle improvement: a high target moves many vertices and still keeps every property") {
  // With a 40° target nearly every vertex is a candidate and most moves are
  // refused by the restricted Delaunay test: the refusals must hold.
  const skin::SkinSurface skin = one_atom();
  geometry::SurfaceMesh mesh = refined_mesh(skin, 3, 0.05, 1);
  refine::AngleImprovementOptions opt;
  opt.target_angle_deg = 40;
  const auto st = improve_and_check(skin, mesh, opt);
  CHECK(st.moves > 10);
  CHECK(st.refused_rdt > 0);
}

TEST_CASE("angle improvement: nothing below the target, nothing moves") {
  const skin::SkinSurface skin = one_atom();
  geometry::SurfaceMesh mesh = refined_mesh(skin, 3, 0.05, 1);
  refine::AngleImprovementOptions opt;
  opt.target_angle_deg = 0.5 * min_angle_deg(mesh);
  std::vector<Vec3> before;
  for (geometry::Vertex v : mesh.vertices()) before.push_back(mesh.position(v));
  const auto st = refine::improve_angles(skin, mesh, opt);
  CHECK(st.low_triangles == 0);
  CHECK(st.moves == 0);
  std::size_t i = 0;
  for (geometry::Vertex v : mesh.vertices()) CHECK(mesh.position(v) == before[i++]);
}

TEST_CASE("angle improvement: deterministic") {
  const skin::SkinSurface skin = two_atoms();
  geometry::SurfaceMesh a = refined_mesh(skin, 3, 0.05, 2);
  geometry::SurfaceMesh b = a;
  const auto sa = refine::improve_angles(skin, a);
  const auto sb = refine::improve_angles(skin, b);
  REQUIRE(sa.moves > 0);
  CHECK(sa.moves == sb.moves);
  for (geometry::Vertex v : a.vertices()) CHECK(a.position(v) == b.position(v));
}

}  // TEST_SUITE

// tests/front/patch_test.cpp: the fallback where the front tangles,
// patch_hole (front/patch.cpp; papers/front/patch.md). A region cut out of a
// closed sweep mesh is re-meshed by the restricted Delaunay triangulation of a
// sample of the skin conforming to the region's boundary: the mesh closes
// again with the same Euler characteristic, every vertex on the skin, every
// face outward, no fold, no two triangles crossing, and every patch triangle
// meets [U].
#include <doctest/doctest.h>

#include <algorithm>
#include <vector>

#include "geometry/check/mesh_checks.h"
#include "morse/critical_points.h"
#include "skin/size_conditions.h"
#include "tests/front/front_fixture.h"
#include "tests/skin/skin_test_util.h"

using namespace skinmesh;
using namespace skinmesh::front::detail;
using namespace skinmesh::test;

namespace {

/// Sweeps and seals the whole skin of fx.
void sweep_closed(FrontState& s) {
  create_initial_front(s);
  while (departure_step(s) || release_saddles(s)) {
  }
  seal_all(s);
}

/// Deletes the faces within `rings` rings of v; returns the live vertices of
/// the boundary loops left (the hole's rim).
std::vector<Vertex> cut_hole(FrontState& s, Vertex v, int rings) {
  std::vector<Vertex> ring{v}, all{v};
  std::vector<geometry::Face> faces;
  for (int r = 0; r < rings; ++r) {
    std::vector<Vertex> next;
    for (Vertex x : ring)
      for (geometry::Face f : s.mesh.faces(x)) {
        faces.push_back(f);
        for (Vertex y : s.mesh.vertices(f))
          if (std::find(all.begin(), all.end(), y) == all.end()) {
            all.push_back(y);
            next.push_back(y);
          }
      }
    ring.swap(next);
  }
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  for (geometry::Face f : faces) s.mesh.delete_face(f);
  std::vector<Vertex> rim;
  for (Vertex x : all)
    if (!s.mesh.is_deleted(x) && !s.mesh.is_isolated(x)) {
      s.set_state(x, VState::Front);
      rim.push_back(x);
    }
  return rim;
}

/// The patch's invariants after patch_hole closed the mesh again.
void check_patched(const FrontState& s, const skin::SkinSurface& skin, long chi, std::size_t first_face) {
  CHECK(front_loops(s) == 0);
  CHECK(euler(s) == chi);
  check_partial_mesh(s, skin);
  geometry::MeshCheckOptions options;
  const geometry::MeshCheckReport report = geometry::check_mesh(s.mesh.to_indexed_mesh(), options);
  CHECK(report.num_self_intersections == 0);
  std::size_t u_violations = 0, patch_faces = 0;
  for (std::size_t i = first_face; i < s.mesh.faces_size(); ++i) {
    const geometry::Face f(static_cast<Index>(i));
    if (s.mesh.is_deleted(f)) continue;
    ++patch_faces;
    std::array<Vertex, 3> c{};
    int k = 0;
    for (Vertex x : s.mesh.vertices(f)) c[k++] = x;
    u_violations += !skin::satisfies_U(s.mesh.position(c[0]), s.mesh.position(c[1]), s.mesh.position(c[2]), s.rho[c[0]],
                                       s.rho[c[1]], s.rho[c[2]], s.run.size);
  }
  CHECK(patch_faces == s.stats.patch_faces);
  CHECK(u_violations == 0);
}

/// The live vertex of smallest rho (on a neck: a hyperboloid patch).
Vertex smallest_rho_vertex(const FrontState& s) {
  Vertex best;
  for (Vertex x : s.mesh.vertices())
    if (!s.mesh.is_deleted(x) && !s.mesh.is_isolated(x) && (!best.is_valid() || s.rho[x] < s.rho[best])) best = x;
  return best;
}

}  // namespace

TEST_SUITE("front operations") {

TEST_CASE("patch_hole: a region cut out of a closed mesh is re-meshed, closed, embedded and under [U]") {
  struct Input {
    const char* name;
    std::vector<geometry::WeightedPoint> points;
    int rings;
  };
  const std::vector<Input> inputs{
      {"one sphere", {{Vec3(0.3, -0.2, 0.1), w_of(1.6, 1.4)}}, 2},
      {"two atoms with a neck", {{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(4.5, 0.8, 0.3), w_of(1.6, 1.4)}}, 3},
      {"the three-ball ring", test::three_ball_ring(), 4},
  };
  for (const Input& in : inputs) {
    CAPTURE(in.name);
    Fixture fx(in.points);
    FrontState s(fx.skin, fx.ms, fx.opt);
    sweep_closed(s);
    REQUIRE(front_loops(s) == 0);
    const long chi = euler(s);
    const Vertex v = smallest_rho_vertex(s);
    const Vec3 at = s.mesh.position(v);
    const std::vector<Vertex> rim = cut_hole(s, v, in.rings);
    REQUIRE(front_loops(s) == 1);
    const std::size_t f0 = s.mesh.faces_size();
    REQUIRE(patch_hole(s, rim, at));
    CHECK(s.stats.patched_holes == 1);
    check_patched(s, fx.skin, chi, f0);
  }
}

TEST_CASE("patch_hole: with an empty vertex list it starts from the front vertices near the given point") {
  Fixture fx({{Vec3(0.3, -0.2, 0.1), w_of(1.6, 1.4)}});
  FrontState s(fx.skin, fx.ms, fx.opt);
  sweep_closed(s);
  const long chi = euler(s);
  const Vertex v = smallest_rho_vertex(s);
  const Vec3 at = s.mesh.position(v);
  cut_hole(s, v, 3);
  const std::size_t f0 = s.mesh.faces_size();
  REQUIRE(patch_hole(s, {}, at));
  check_patched(s, fx.skin, chi, f0);
}

TEST_CASE("patch_hole: off, it refuses and leaves the mesh as it was") {
  Fixture fx({{Vec3(0.3, -0.2, 0.1), w_of(1.6, 1.4)}});
  fx.opt.patch_fallback = false;
  FrontState s(fx.skin, fx.ms, fx.opt);
  sweep_closed(s);
  const Vertex v = smallest_rho_vertex(s);
  const std::vector<Vertex> rim = cut_hole(s, v, 2);
  const std::size_t faces = s.mesh.n_faces();
  CHECK_FALSE(patch_hole(s, rim, s.mesh.position(rim.front())));
  CHECK(s.mesh.n_faces() == faces);
  CHECK(front_loops(s) == 1);
  CHECK(s.stats.patched_holes == 0);
}

}  // TEST_SUITE

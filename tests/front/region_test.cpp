// tests/front/region_test.cpp: the sweep of one region of the decomposed sweep
// (front/region.h, papers/decompose/README.md) against what the
// slab must be: its mesh lies on the skin between the cuts, its boundary is
// exactly the lower cut curves' samples (in their order) plus one parked rim
// per upper cut curve, its Euler characteristic is the alternating count of the critical
// points inside the slab (Morse theory for a surface bounded by level
// curves), and its area is the analytic zone's on a sphere.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "core/errors.h"
#include "front/region.h"
#include "morse/critical_points.h"
#include "morse/level_curves.h"
#include "morse/morse_smale_complex.h"
#include "skin/molecule_io.h"
#include "skin/skin_surface.h"
#include "skin/vertex_data.h"

using namespace skinmesh;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The slab between the cuts at heights lower and upper (±infinity: none).
front::Region make_slab(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, double lower, double upper) {
  front::Region slab;
  slab.lower = lower;
  slab.upper = upper;
  if (std::isfinite(lower)) slab.lower_curves = morse::level_curves(skin, ms, lower);
  return slab;
}

/// V - E + F of a garbage-collected mesh.
long euler_characteristic(const geometry::SurfaceMesh& m) {
  return static_cast<long>(m.n_vertices()) - static_cast<long>(m.n_edges()) + static_cast<long>(m.n_faces());
}

/// Sum of (-1)^index over every critical point of the height strictly
/// between the cuts (live or cancelled: both are critical points of h on F).
long expected_euler_characteristic(const morse::MorseSmaleComplex& ms, double lower, double upper) {
  long chi = 0;
  for (const morse::CriticalPoint& cp : ms.critical) {
    if (cp.height > lower && cp.height < upper) chi += cp.kind == morse::CriticalKind::Saddle ? -1 : 1;
  }
  return chi;
}

double mesh_area(const geometry::SurfaceMesh& m) {
  double a = 0;
  for (geometry::Face f : m.faces()) {
    std::vector<Vec3> p;
    for (geometry::Vertex v : m.vertices(f)) p.push_back(m.position(v));
    a += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
  }
  return a;
}

/// Every property of a slab's mesh that does not depend on the input's shape:
/// vertices on the skin and between the cuts (none within (park_factor - 1)
/// r_min of the upper cut), faces outward, the lower loops exactly the
/// curves' samples (traversed against the curve: the slab lies above), every
/// other boundary loop a rim, one rim per upper cut curve, and the Euler
/// characteristic of Morse theory. The lower loops are traversed in the
/// curves' order: a curve oriented by n × e has the part below on its left.
void check_slab(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms, const front::Region& slab,
                const front::RegionResult& res) {
  const geometry::SurfaceMesh& m = res.mesh;
  const Vec3 e = ms.height_direction;
  REQUIRE(m.has_vertex_property(skin::kVertexCell));
  const skin::VertexRhos rho(skin.mixed_complex(), m);
  const skin::VertexNormals normal(skin.mixed_complex(), m);
  std::size_t off_skin = 0, below = 0, above = 0, inward = 0;
  Index hint = kInvalidIndex;
  for (geometry::Vertex v : m.vertices()) {
    const Vec3 p = m.position(v);
    const skin::SkinSample s = skin.sample(p, hint);
    hint = s.cell;
    if (std::abs(s.f) / s.gradient.norm() > 1e-9) ++off_skin;
    if (e.dot(p) < slab.lower - 1e-9) ++below;
    // No fan reaches above upper - (park_factor - 1) r sin(theta) (the
    // parking height scales with the slope, theta the angle between the
    // normal and e); a projection may add a little.
    const double cos_theta = e.dot(normal[v]);
    const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
    if (e.dot(p) > slab.upper - 0.5 * (slab.park_factor - 1) * front::SweepOptions{}.disc_factor * rho[v] * sin_theta)
      ++above;
  }
  for (geometry::Face f : m.faces()) {
    std::vector<geometry::Vertex> c;
    for (geometry::Vertex v : m.vertices(f)) c.push_back(v);
    const Vec3 nt = (m.position(c[1]) - m.position(c[0])).cross(m.position(c[2]) - m.position(c[0]));
    for (geometry::Vertex v : c)
      if (nt.dot(normal[v]) <= 0) ++inward;
  }
  CHECK(off_skin == 0);
  CHECK(below == 0);
  CHECK(above == 0);
  CHECK(inward == 0);

  // The lower loops: the curves' samples, each one boundary loop.
  REQUIRE(res.lower_loops.size() == slab.lower_curves.size());
  std::size_t first = 0;
  for (std::size_t k = 0; k < slab.lower_curves.size(); ++k) {
    const auto& curve = slab.lower_curves[k];
    const auto& loop = res.lower_loops[k];
    REQUIRE(loop.size() == curve.points.size());
    for (std::size_t j = 0; j < loop.size(); ++j) {
      CHECK(loop[j] == first + j);
      CHECK(m.position(geometry::Vertex(loop[j])) == curve.points[j]);
    }
    first += loop.size();
    // The boundary half-edge out of sample j goes to sample j + 1: the part
    // below the cut, not meshed here, is on its left.
    for (std::size_t j = 0; j < loop.size(); ++j) {
      const geometry::Halfedge h =
          m.find_halfedge(geometry::Vertex(loop[j]), geometry::Vertex(loop[(j + 1) % loop.size()]));
      REQUIRE(h.is_valid());
      CHECK(m.is_boundary(h));
    }
  }
  const std::size_t n_loops = m.boundary_loops().size();
  CHECK(n_loops == res.lower_loops.size() + res.upper_rims.size());
  if (std::isfinite(slab.upper)) {
    CHECK(res.upper_rims.size() == morse::level_curves(skin, ms, slab.upper).size());
  } else {
    CHECK(res.upper_rims.empty());
    CHECK(res.parked == 0);
  }
  CHECK(euler_characteristic(m) == expected_euler_characteristic(ms, slab.lower, slab.upper));
  CHECK(res.stats.left_holes == 0);
}

/// Heights on a fine grid of the critical heights' range whose cut stays
/// clear of every protecting sphere (morse::cut_clearance >= clearance).
std::vector<double> clear_heights(const morse::MorseSmaleComplex& ms, int n, double clearance) {
  double lo = kInf, hi = -kInf;
  for (const auto& cp : ms.critical) {
    lo = std::min(lo, cp.height), hi = std::max(hi, cp.height);
  }
  std::vector<double> out;
  for (int i = 1; i < n; ++i) {
    const double c = lo + (hi - lo) * i / n;
    if (morse::cut_clearance(ms, c) >= clearance) out.push_back(c);
  }
  return out;
}

}  // namespace

TEST_CASE("slab of one ball: annulus, cap and bowl, each with the analytic zone's area") {
  const double R = 1.7;
  const Vec3 centre(0.3, -0.2, 0.5);
  const skin::SkinSurface skin({{centre, 2 * R * R}});
  const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, morse::default_height_direction());
  const double h0 = centre.dot(ms.height_direction);
  const double two_pi_r = 2 * kPi * R;

  SUBCASE("through the middle: an annulus between the lower curve and one rim") {
    const front::Region slab = make_slab(skin, ms, h0 - 0.4 * R, h0 + 0.5 * R);
    REQUIRE(slab.lower_curves.size() == 1);
    const front::RegionResult res = front::sweep_region(skin, ms, slab);
    check_slab(skin, ms, slab, res);
    CHECK(euler_characteristic(res.mesh) == 0);
    REQUIRE(res.upper_rims.size() == 1);
    CHECK(res.parked > 0);
    // The mesh covers the zone from the lower cut up to its rim, once: its
    // area lies between the zones up to the rim's lowest and highest vertex
    // (a sphere zone's area is 2 pi R times its height), less the chords'.
    double rim_lo = kInf, rim_hi = -kInf;
    for (Index v : res.upper_rims[0]) {
      const double h = res.mesh.position(geometry::Vertex(v)).dot(ms.height_direction);
      rim_lo = std::min(rim_lo, h), rim_hi = std::max(rim_hi, h);
    }
    const double area = mesh_area(res.mesh);
    CHECK(area > 0.97 * two_pi_r * (rim_lo - slab.lower));
    CHECK(area < two_pi_r * (rim_hi - slab.lower));
  }
  SUBCASE("over the top: a cap sealed at the maximum") {
    const front::Region slab = make_slab(skin, ms, h0 + 0.2 * R, kInf);
    const front::RegionResult res = front::sweep_region(skin, ms, slab);
    check_slab(skin, ms, slab, res);
    CHECK(euler_characteristic(res.mesh) == 1);
    const double area = mesh_area(res.mesh);
    CHECK(area > 0.97 * two_pi_r * (h0 + R - slab.lower));
    CHECK(area < two_pi_r * (h0 + R - slab.lower));
  }
  SUBCASE("from the bottom: a bowl grown from the minimum up to one rim") {
    const front::Region slab = make_slab(skin, ms, -kInf, h0 - 0.1 * R);
    const front::RegionResult res = front::sweep_region(skin, ms, slab);
    check_slab(skin, ms, slab, res);
    CHECK(euler_characteristic(res.mesh) == 1);
    CHECK(res.upper_rims.size() == 1);
    CHECK(res.stats.creations == 1);
  }
  SUBCASE("the default region is the whole skin: a closed sphere, nothing parked") {
    const front::RegionResult res = front::sweep_region(skin, ms, front::Region{});
    CHECK(euler_characteristic(res.mesh) == 2);
    CHECK(res.mesh.boundary_loops().empty());
    CHECK(res.parked == 0);
    CHECK(res.upper_rims.empty());
    CHECK(res.lower_loops.empty());
    CHECK(mesh_area(res.mesh) > 0.97 * 4 * kPi * R * R);
    CHECK(mesh_area(res.mesh) < 4 * kPi * R * R);
  }
  SUBCASE("bad slabs are refused") {
    front::Region slab = make_slab(skin, ms, h0, h0 - 0.1);
    CHECK_THROWS_AS(front::sweep_region(skin, ms, slab), std::invalid_argument);
    slab = make_slab(skin, ms, h0 - 0.5, h0 + 0.5);
    slab.park_factor = 0.5;
    CHECK_THROWS_AS(front::sweep_region(skin, ms, slab), std::invalid_argument);
    slab.park_factor = 2;
    std::reverse(slab.lower_curves[0].points.begin(), slab.lower_curves[0].points.end());
    CHECK_THROWS_AS(front::sweep_region(skin, ms, slab), TopologyError);
    slab = make_slab(skin, ms, h0 - 0.5, h0 + 0.5);
    slab.owns.assign(ms.critical.size() + 1, 1);
    CHECK_THROWS_AS(front::sweep_region(skin, ms, slab), std::invalid_argument);
  }
}

TEST_CASE("a region given by owns alone (a group of components): the owned ball's closed sphere, nothing else") {
  const double R = 1.3;
  const skin::SkinSurface skin({{Vec3(0, 0, 0), 2 * R * R}, {Vec3(9, 0.5, -0.3), 2 * R * R}});
  const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, morse::default_height_direction());
  front::Region group;
  group.owns.assign(ms.critical.size(), 0);
  for (std::size_t c = 0; c < ms.critical.size(); ++c) group.owns[c] = ms.critical[c].position.x() < 4.5;
  front::SweepResult res = front::sweep_mesh(skin, ms, group);
  res.mesh.garbage_collection();
  CHECK(euler_characteristic(res.mesh) == 2);
  CHECK(res.mesh.boundary_loops().empty());
  CHECK(res.stats.creations == 1);
  for (geometry::Vertex v : res.mesh.vertices()) CHECK(res.mesh.position(v).norm() == doctest::Approx(R).epsilon(1e-6));
  CHECK(mesh_area(res.mesh) > 0.97 * 4 * kPi * R * R);
  // The whole skin: both spheres.
  front::SweepResult whole = front::sweep_mesh(skin, ms, front::Region{});
  whole.mesh.garbage_collection();
  CHECK(euler_characteristic(whole.mesh) == 4);
  // A region with a cut is sweep_region's.
  group.upper = 0.5;
  CHECK_THROWS_AS(front::sweep_mesh(skin, ms, group), std::invalid_argument);
}

TEST_CASE("slabs of a standing ring and of crambin: Morse theory's Euler characteristic, one rim per upper curve") {
  struct Case {
    std::string name;
    std::vector<geometry::WeightedPoint> points;
  };
  std::vector<Case> cases;
  {
    // Twelve balls on a circle in a plane that holds the height direction, so
    // that the slabs cross the ring's saddles and split and join its front.
    const Vec3 e = morse::default_height_direction();
    const Vec3 u = e.unitOrthogonal();
    Case ring{"standing ring of 12 balls", {}};
    for (int k = 0; k < 12; ++k) {
      const double t = 2 * kPi * k / 12 + 0.1;
      ring.points.push_back({4.0 * (std::cos(t) * e + std::sin(t) * u), 2 * 1.4 * 1.4});
    }
    cases.push_back(ring);
  }
  const skin::Molecule crambin = skin::read_molecule(std::string(SKINMESH_DATA) + "/crambin_1crn.pdb");
  cases.push_back({"crambin, probe 1.4", skin::weighted_points(crambin, 1.4)});
  for (const Case& cs : cases) {
    CAPTURE(cs.name);
    const skin::SkinSurface skin(cs.points);
    const morse::MorseSmaleComplex ms = morse::build_morse_smale_complex(skin, morse::default_height_direction());
    const std::vector<double> heights = clear_heights(ms, 200, 0.3);
    // Cuts at the clear heights, each the first at least 0.6 rho_max above
    // the last (a slab must be thicker than three disc radii, 0.555 rho:
    // sweep_region), and the slabs they make.
    double rho_max = 0;
    for (const auto& p : skin.points()) rho_max = std::max(rho_max, std::sqrt(p.w / 2));
    std::vector<double> cuts{-kInf};
    for (double c : heights)
      if (cuts.size() == 1 || c > cuts.back() + 0.6 * rho_max) cuts.push_back(c);
    REQUIRE(cuts.size() >= 6);
    REQUIRE(cuts.size() >= 4);
    cuts.push_back(kInf);
    long chi = 0;
    for (std::size_t i = 0; i + 1 < cuts.size(); ++i) {
      CAPTURE(i);
      const front::Region slab = make_slab(skin, ms, cuts[i], cuts[i + 1]);
      const front::RegionResult res = front::sweep_region(skin, ms, slab);
      check_slab(skin, ms, slab, res);
      chi += euler_characteristic(res.mesh);
    }
    // The slabs' characteristics add up to the skin's (the cut curves are
    // circles, of characteristic 0).
    CHECK(chi == expected_euler_characteristic(ms, -kInf, kInf));
  }
}

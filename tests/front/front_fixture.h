// tests/front/front_fixture.h: what the tests of the sweep's operations
// share — a skin with its Morse–Smale complex kept alive for a FrontState, and
// the invariants every partial mesh must keep: vertices on the skin, faces
// outward at their three corners, no fold in any tangent plane.
#pragma once

#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <vector>

#include "front/operations.h"
#include "morse/critical_points.h"
#include "morse/morse_smale_complex.h"
#include "skin/skin_surface.h"

namespace skinmesh::test {

using front::detail::FrontState;
using geometry::Vertex;

inline double w_of(double r, double probe) { return 2 * (r + probe) * (r + probe); }

/// A skin with its Morse–Smale complex, kept alive for a Sweep.
struct Fixture {
  skin::SkinSurface skin;
  morse::MorseSmaleComplex ms;
  front::SweepOptions opt;
  explicit Fixture(std::vector<geometry::WeightedPoint> pts, Vec3 e = morse::default_height_direction())
      : skin(std::move(pts)), ms(morse::build_morse_smale_complex(skin, e)) {}
  Index first_live(morse::CriticalKind kind) const {
    for (std::size_t i = 0; i < ms.critical.size(); ++i)
      if (ms.live[i] && ms.critical[i].kind == kind) return static_cast<Index>(i);
    return kInvalidIndex;
  }
};

/// Number of boundary loops (front polygons) of the partial mesh.
inline std::size_t front_loops(const FrontState& s) { return s.mesh.boundary_loops().size(); }

/// V - E + F of the partial mesh (isolated and deleted vertices excluded).
inline long euler(const FrontState& s) {
  const auto& m = s.mesh;
  long v = 0;
  for (Vertex x : m.vertices())
    if (!m.is_deleted(x) && !m.is_isolated(x)) ++v;
  return v - static_cast<long>(m.n_edges()) + static_cast<long>(m.n_faces());
}

/// The invariants of a partial mesh of the skin: every vertex on the skin,
/// every face outward at its three corners, no fold at any vertex.
inline void check_partial_mesh(const FrontState& s, const skin::SkinSurface& skin) {
  const auto& m = s.mesh;
  std::size_t far = 0, inward = 0, folded = 0;
  for (Vertex v : m.vertices()) {
    if (m.is_deleted(v) || m.is_isolated(v)) continue;
    const skin::SkinSample smp = skin.sample(m.position(v), kInvalidIndex);
    if (std::abs(smp.f) / smp.gradient.norm() > 1e-9) ++far;
    if (std::abs(front::detail::fold_excess(s, v)) > 1 * kDegree) ++folded;
  }
  for (geometry::Face f : m.faces()) {
    if (m.is_deleted(f)) continue;
    std::array<Vertex, 3> c{};
    int i = 0;
    for (Vertex v : m.vertices(f)) c[i++] = v;
    const Vec3 nt = (m.position(c[1]) - m.position(c[0])).cross(m.position(c[2]) - m.position(c[0]));
    for (Vertex v : c)
      if (nt.dot(s.normal[v]) <= 0) ++inward;
  }
  CHECK(far == 0);
  CHECK(inward == 0);
  CHECK(folded == 0);
}

/// Sweeps `s` (made with fx.opt's wings switched off: wing_angle_deg and
/// forced_wing_angle_deg 0) until some free front vertex has a front angle
/// below 85° that wing() would close at the paper's 90°; returns it (invalid
/// after 400 departures without one). fx.opt is left with wings off.
inline Vertex sweep_to_narrow_corner(Fixture& fx, FrontState& s) {
  using namespace front::detail;
  create_initial_front(s);
  for (int step = 0; step < 400; ++step) {
    REQUIRE(departure_step(s));
    for (Vertex v : s.mesh.vertices())
      if (!s.mesh.is_deleted(v) && s.mesh.is_boundary(v) && s.state[v] == VState::Front &&
          corner(s, v).angle < 85 * kDegree) {
        fx.opt.wing_angle_deg = 90;  // the state reads its options by reference
        const bool takes = wing_refusal(s, v, false) == nullptr;
        fx.opt.wing_angle_deg = 0;
        if (takes) return v;
      }
  }
  return Vertex();
}

/// Two overlapping atoms swept with the wings off until a free front vertex
/// `v` has a narrow corner that wing() would close (sweep_to_narrow_corner;
/// `v` invalid if none came), then the paper's wing threshold (90°) set
/// again; forced wings stay off.
struct NarrowCorner {
  Fixture fx{{{Vec3(0, 0, 0), w_of(1.6, 1.4)}, {Vec3(2.4, 0.3, 0.2), w_of(1.7, 1.4)}}};
  FrontState s;
  Vertex v;
  NarrowCorner() : s(fx.skin, fx.ms, wings_off(fx.opt)), v(sweep_to_narrow_corner(fx, s)) {
    fx.opt.wing_angle_deg = 90;
  }

 private:
  static const front::SweepOptions& wings_off(front::SweepOptions& opt) {
    opt.wing_angle_deg = 0;
    opt.forced_wing_angle_deg = 0;
    return opt;
  }
};

}  // namespace skinmesh::test

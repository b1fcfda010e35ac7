// front/sweep_mesher.h: the adaptive sweeping triangulation — an advancing
// front that grows from the minima of the height function upwards, bridges at
// saddles and seals at maxima, with triangle sizes adapted to the local length
// scale rho. Cheng & Shi 2004 §4.1 (Algorithm 1, creation / creep / wing /
// bridge / seal), §4.2 (tangent-disc radius). Notes: papers/front/sweep_mesher.md
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "geometry/indexed_mesh.h"
#include "geometry/surface_mesh.h"
#include "morse/morse_smale_complex.h"
#include "refine/size_conditions.h"
#include "skin/skin_surface.h"

namespace skinmesh::front {

/// Options of the sweep.
struct SweepOptions {
  /// C and Q of conditions [L], [U] (Cheng & Shi §2.2).
  refine::SizeConstants size;
  /// Tangent-disc radius r_a = disc_factor * rho(a) (Cheng & Shi §4.2). Must lie
  /// in the window (2C/(Q-2C), 2CQ sqrt((1+CQ)(1+3CQ))/(1+2CQ)²] = (0.1074,
  /// 0.2077] for the default C, Q. Default 0.185: below 0.1853 the fan
  /// triangles satisfy [U] themselves (skin-math §8 note 4).
  double disc_factor = 0.185;
  /// Run the local refinement (flip, contraction, insertion) after the sweep.
  bool refine = true;
  /// Called now and then with a stage name and the fraction done (0..1).
  std::function<void(const std::string& stage, double fraction)> progress;

  // Debugging aids (papers/front/sweep_mesher.md, "Debugging aids").
  /// After every operation, check that the tangent angles around the vertices
  /// of the new triangles make 360° (no fold); throw TopologyError naming the
  /// operation otherwise.
  bool paranoid = false;
  /// Called with one line per decision of the sweep (creep, wing refusals,
  /// contacts, bridges, seals); empty: no trace.
  std::function<void(const std::string& line)> trace;
  /// Stop with TopologyError after this many departures (negative: no limit).
  long max_steps = -1;
  /// If not empty, the partial mesh is written here before the seal, when a
  /// paranoid check fails, and when max_steps stops the sweep.
  std::string dump_path;
};

/// Counters of the sweep (Algorithm 1's operations and the refinement).
struct SweepStats {
  std::size_t creations = 0, creeps = 0, wings = 0, bridges = 0, seals = 0;
  std::size_t held = 0;           ///< departure vertices stopped in a protecting sphere
  std::size_t deferred = 0;       ///< creeps postponed because the fan would fold (Figure 7)
  std::size_t bridge_rows = 0;    ///< ladder rows added by bridges
  std::size_t contacts = 0;       ///< front parts joined by the safety net (a deviation, Q2.3)
  std::size_t stuck = 0;          ///< departure vertices left for the seal (no fan fits, Figure 7)
  std::size_t enlarged_holes = 0;  ///< tangled holes re-opened by deleting the faces around them
  std::size_t collisions = 0;     ///< fans that would have come within r/2 of another front part
  std::size_t released = 0;       ///< saddles whose holds were released unbridged (Q6.4)
  std::size_t flips = 0, contractions = 0, insertions = 0;  ///< local refinement (§4.3)
  std::size_t refine_rounds = 0;
  std::size_t L_left = 0, U_left = 0;  ///< [L] / [U] violations the refinement left
};

/// The mesh produced by the sweep with its per-vertex data.
struct SweepResult {
  geometry::IndexedMesh mesh;  ///< positions, triangles (CCW outward), normals, atom
  SweepStats stats;
};

/// Meshes the skin. `ms` gives the critical points (live ones after
/// simplification), their protecting spheres and the height direction.
/// Throws TopologyError when the front cannot be closed consistently (a saddle
/// whose two sides never arrive, a hole without a maximum), GeometryError when
/// a projection fails.
SweepResult sweep_mesh(const skin::SkinSurface& skin, const morse::MorseSmaleComplex& ms,
                       const SweepOptions& opt = {});

}  // namespace skinmesh::front

// tests/stress/generator.h: the seeded generator of the stress suite's inputs.
// Each case is a named list of atoms (centre, radius, Å) plus a probe radius
// (Å); the mesher turns atom i into the weighted point (z_i, w_i) with
// w_i = 2 (r_i + probe)² (skin::weighted_points, Cheng & Shi §2.1), i.e. an
// unshrunk ball of radius sqrt(2) (r_i + probe).
//
// Families (names start with the family): random clusters, pseudo-proteins,
// simple cubic / fcc / bcc lattices, nested shells ("onions"), rings, helices
// and a trefoil knot, near-threshold pairs / triangles / tetrahedra
// (thin necks, gaps, closing holes and voids), duplicate and nested atoms,
// and the fallback's and the low-resolution classes (membranes, cages,
// dense packings, channels, all-atom models with clashes);
// about one case in two also appears rotated and translated by up to 1e6 Å
// (name suffix "/rt").
//
// Determinism: every case has its own std::mt19937_64 seeded from the suite
// seed and the case's descriptor; uniform and normal deviates are computed
// here (not by std::*_distribution), so the inputs are the same with every
// standard library.
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "core/types.h"
#include "geometry/kernel/weighted_point.h"
#include "skin/molecule.h"

namespace skinmesh::stress {

/// The probe radii (Å) the suite draws from.
inline constexpr double kProbes[] = {0.0, 0.5, 1.4, 3.0};

/// Seeded random numbers with library-independent deviates.
class Rng {
 public:
  /// A generator seeded with `seed` (std::mt19937_64).
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  /// Uniform deviate in [0, 1) with 53 random bits.
  double uniform();
  /// Uniform deviate in [a, b).
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  /// Uniform integer in [0, n), n > 0.
  std::size_t index(std::size_t n);
  /// Standard normal deviate (Box–Muller, one of the pair).
  double normal();
  /// Uniformly distributed unit vector.
  Vec3 unit_vector();
  /// Uniformly distributed rotation (Shoemake's quaternion method).
  Mat3 rotation();
  /// One of kProbes, uniformly.
  double probe();

 private:
  std::mt19937_64 engine_;
};

/// SplitMix64 finaliser: a well-mixed 64-bit hash of x.
std::uint64_t mix64(std::uint64_t x);

/// The seed of the case with descriptor `key` in the suite of seed
/// `suite_seed`: mix64 of the suite seed and the FNV-1a hash of the key, so a
/// case's content does not depend on which other cases are generated.
std::uint64_t case_seed(std::uint64_t suite_seed, const std::string& key);

/// One atom of a stress case: centre (Å) and van der Waals radius (Å, > 0).
struct StressAtom {
  Vec3 centre = Vec3::Zero();
  double radius = 1.7;
};

/// A named stress input.
struct StressCase {
  /// Unique name, "family/parameters/pPROBE[/rt]".
  std::string name;
  /// The family: cluster, protein, lattice, shell, ring, helix, threshold, duplicate,
  /// membrane, cage, packing, channel, lowres.
  std::string family;
  /// Seed of the case's own generator (see case_seed()); with the suite seed
  /// and the name it reproduces the case.
  std::uint64_t seed = 0;
  /// Probe radius (Å): weights w = 2 (r + probe)².
  double probe = 0.0;
  std::vector<StressAtom> atoms;
  /// Exactly on a topology threshold (two unshrunk balls tangent, a lattice
  /// or ring whose holes or voids close exactly, ...), exactly in floating
  /// point or up to the rounding of the weights: either a mesh that passes
  /// every check or the "singular skin" InputError is acceptable.
  bool singular = false;
  /// Rotated by a random rotation and translated by up to 1e6 Å.
  bool transformed = false;
  /// Height direction of the sweep (unit); zero: the pipeline's default.
  Vec3 direction = Vec3::Zero();
  /// One line on what the case tests (thresholds, spacings in Å).
  std::string note;
};

/// The default suite (about 520 cases) of seed `suite_seed`, in family order.
std::vector<StressCase> generate_suite(std::uint64_t suite_seed);

/// `count` further random cases (clusters, pseudo-proteins, rings, threshold
/// pairs, each possibly rotated and translated) for longer runs, named
/// ".../extraK".
std::vector<StressCase> generate_extra(std::uint64_t suite_seed, std::size_t count);

/// The weighted points of a case, w = 2 (r + probe)² (Å²), via skin::weighted_points.
std::vector<geometry::WeightedPoint> weighted_points(const StressCase& c);

/// The case's atoms as a skin::Molecule (source = the case name).
skin::Molecule to_molecule(const StressCase& c);

/// The case rotated by a random rotation about its centroid and translated by
/// a random vector of length 10^u Å, u uniform in [0, 6]; drawn from `rng`.
StressCase rotated_translated(const StressCase& c, Rng& rng);

}  // namespace skinmesh::stress

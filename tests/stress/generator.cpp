// tests/stress/generator.cpp: the families of the stress suite
// (tests/stress/generator.h). Lengths in Å. Threshold spacings are derived
// from the unshrunk radius R = sqrt(w) = sqrt(2) (r + probe) of
// skin::atom_weight(), computed exactly as the mesher computes it.
#include "tests/stress/generator.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>

#include "skin/molecule_io.h"
#include "skin/skin_surface.h"

namespace skinmesh::stress {

// Rng -------------------------------------------------------------------------

double Rng::uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

std::size_t Rng::index(std::size_t n) { return static_cast<std::size_t>(uniform() * static_cast<double>(n)) % n; }

double Rng::normal() {
  double u1 = uniform();
  while (u1 <= 0.0) u1 = uniform();
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

Vec3 Rng::unit_vector() {
  const double z = uniform(-1.0, 1.0);
  const double phi = uniform(0.0, 2.0 * std::numbers::pi);
  const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vec3(s * std::cos(phi), s * std::sin(phi), z);
}

Mat3 Rng::rotation() {
  const double u1 = uniform(), u2 = uniform(), u3 = uniform();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const double t2 = 2.0 * std::numbers::pi * u2, t3 = 2.0 * std::numbers::pi * u3;
  const Eigen::Quaterniond q(b * std::cos(t3), a * std::sin(t2), a * std::cos(t2), b * std::sin(t3));
  return q.normalized().toRotationMatrix();
}

double Rng::probe() { return kProbes[index(std::size(kProbes))]; }

std::uint64_t mix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t case_seed(std::uint64_t suite_seed, const std::string& key) {
  std::uint64_t h = 0xcbf29ce484222325ULL;  // FNV-1a
  for (unsigned char ch : key) h = (h ^ ch) * 0x100000001b3ULL;
  return mix64(mix64(suite_seed) ^ h);
}

// Conversions ------------------------------------------------------------------

skin::Molecule to_molecule(const StressCase& c) {
  skin::Molecule m;
  m.source = c.name;
  m.atoms.reserve(c.atoms.size());
  int serial = 0;
  for (const StressAtom& a : c.atoms) {
    skin::Atom atom;
    atom.centre = a.centre;
    atom.radius = a.radius;
    atom.serial = ++serial;
    m.atoms.push_back(std::move(atom));
  }
  return m;
}

std::vector<geometry::WeightedPoint> weighted_points(const StressCase& c) {
  return skin::weighted_points(to_molecule(c), c.probe);
}

StressCase rotated_translated(const StressCase& c, Rng& rng) {
  StressCase out = c;
  const Mat3 rot = rng.rotation();
  const double magnitude = std::pow(10.0, rng.uniform(0.0, 6.0));
  const Vec3 shift = magnitude * rng.unit_vector();
  Vec3 centroid = Vec3::Zero();
  for (const StressAtom& a : c.atoms) centroid += a.centre;
  if (!c.atoms.empty()) centroid /= static_cast<double>(c.atoms.size());
  for (StressAtom& a : out.atoms) a.centre = rot * (a.centre - centroid) + centroid + shift;
  out.transformed = true;
  out.name += "/rt";
  char buf[96];
  std::snprintf(buf, sizeof buf, "; rotated, translated by %.3g Å", magnitude);
  out.note += buf;
  return out;
}

namespace {

/// Short decimal text of x ("1.4", "0.001", "1e-06").
std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", x);
  return buf;
}

/// Unshrunk ball radius R = sqrt(w) (Å) of an atom of radius r and probe p,
/// with w computed exactly as skin::atom_weight computes it.
double unshrunk(double r, double p) { return std::sqrt(skin::atom_weight(r, p)); }

/// Collects the cases of one suite; `begin` seeds a case from its descriptor.
struct Suite {
  std::uint64_t seed;
  std::vector<StressCase> cases;

  /// A case of `family` with descriptor `key` (its name before the probe),
  /// seeded from the descriptor.
  StressCase begin(const std::string& family, const std::string& key) const {
    StressCase c;
    c.family = family;
    c.name = family + "/" + key;
    c.seed = case_seed(seed, c.name);
    return c;
  }
  /// Finishes the name with the probe and stores the case.
  void add(StressCase c) {
    c.name += "/p" + num(c.probe);
    cases.push_back(std::move(c));
  }
  /// begin() then add() for a case given by its atoms, probe radius (Å),
  /// singularity flag and note.
  void add(const std::string& family, const std::string& key, double probe, std::vector<StressAtom> atoms,
           bool singular, const std::string& note) {
    StressCase c = begin(family, key);
    c.probe = probe;
    c.atoms = std::move(atoms);
    c.singular = singular;
    c.note = note;
    add(std::move(c));
  }
};

/// Points on a sphere of radius `rs` about the origin, n of them on a
/// Fibonacci spiral, randomly rotated.
std::vector<Vec3> sphere_points(int n, double rs, Rng& rng) {
  std::vector<Vec3> pts;
  const Mat3 rot = rng.rotation();
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n;
    const double s = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = golden * i;
    pts.push_back(rs * (rot * Vec3(s * std::cos(phi), s * std::sin(phi), z)));
  }
  return pts;
}

// Random clusters -----------------------------------------------------------------

/// Atoms uniform in a cube whose side gives the requested van der Waals
/// packing fraction; radii uniform in [1.2, 2.0] Å.
void clusters(Suite& s) {
  const struct {
    const char* name;
    double fraction;
  } densities[] = {{"sparse", 0.03}, {"medium", 0.12}, {"dense", 0.35}};
  const int sizes[] = {5, 8, 12, 20, 30, 45, 60, 90, 130, 200};
  for (const auto& d : densities)
    for (int n : sizes) {
      StressCase c = s.begin("cluster", std::string(d.name) + "/n" + std::to_string(n));
      Rng rng(c.seed);
      c.probe = rng.probe();
      const double side = std::cbrt(n * 4.0 / 3.0 * kPi * 1.6 * 1.6 * 1.6 / d.fraction);
      for (int i = 0; i < n; ++i)
        c.atoms.push_back(
            {Vec3(rng.uniform(0, side), rng.uniform(0, side), rng.uniform(0, side)), rng.uniform(1.2, 2.0)});
      c.note = "uniform in a cube of side " + num(side) + " Å, packing fraction " + num(d.fraction);
      s.add(std::move(c));
    }
}

// Pseudo-proteins ---------------------------------------------------------------------

/// A random self-avoiding backbone N–CA–C (bond 1.5 Å, bond angle 111°,
/// random torsion, no atom closer than 2.5 Å to earlier ones but its two
/// predecessors), a carbonyl O on every C and a side chain of 1–4 atoms on
/// most CA; radii N 1.55, C 1.7, O 1.52, CH2 1.9 Å. Stops at n atoms.
std::vector<StressAtom> pseudo_protein(int n, Rng& rng) {
  constexpr double kBond = 1.5;
  const double theta = (180.0 - 111.0) * kPi / 180.0;
  std::vector<StressAtom> atoms;
  std::vector<std::size_t> backbone;
  auto min_distance = [&](const Vec3& x, std::size_t skip_a, std::size_t skip_b) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < atoms.size(); ++i)
      if (i != skip_a && i != skip_b) best = std::min(best, (atoms[i].centre - x).norm());
    return best;
  };
  auto side_atom = [&](std::size_t anchor, double radius) -> bool {
    Vec3 best_x = Vec3::Zero();
    double best_d = -1;
    for (int attempt = 0; attempt < 40; ++attempt) {
      const Vec3 x = atoms[anchor].centre + kBond * rng.unit_vector();
      const double d = min_distance(x, anchor, anchor);
      if (d > best_d) best_d = d, best_x = x;
      if (d >= 2.2) break;
    }
    if (best_d < 1.2) return false;
    atoms.push_back({best_x, radius});
    return true;
  };
  Vec3 dir = rng.unit_vector();
  atoms.push_back({Vec3::Zero(), 1.55});  // N
  backbone.push_back(0);
  const double backbone_radii[3] = {1.55, 1.7, 1.7};  // N, CA, C
  for (int k = 1; static_cast<int>(atoms.size()) < n; ++k) {
    const std::size_t prev = backbone.back();
    const std::size_t prev2 = backbone.size() >= 2 ? backbone[backbone.size() - 2] : prev;
    // Orthonormal frame about the previous bond.
    Vec3 e1 = dir.unitOrthogonal();
    Vec3 e2 = dir.cross(e1);
    Vec3 best_x = Vec3::Zero(), best_u = dir;
    double best_d = -1;
    for (int attempt = 0; attempt < 60; ++attempt) {
      const double phi = rng.uniform(0, 2 * kPi);
      const Vec3 u = std::cos(theta) * dir + std::sin(theta) * (std::cos(phi) * e1 + std::sin(phi) * e2);
      const Vec3 x = atoms[prev].centre + kBond * u;
      const double d = min_distance(x, prev, prev2);
      if (d > best_d) best_d = d, best_x = x, best_u = u;
      if (d >= 2.5) break;
    }
    atoms.push_back({best_x, backbone_radii[k % 3]});
    backbone.push_back(atoms.size() - 1);
    dir = best_u;
    const std::size_t here = atoms.size() - 1;
    if (static_cast<int>(atoms.size()) >= n) break;
    if (k % 3 == 2) {
      side_atom(here, 1.52);                          // carbonyl O
    } else if (k % 3 == 1 && rng.uniform() < 0.85) {  // CA: side chain
      const int length = 1 + static_cast<int>(rng.index(4));
      std::size_t anchor = here;
      for (int j = 0; j < length && static_cast<int>(atoms.size()) < n; ++j) {
        const double u = rng.uniform();
        const double radius = j + 1 == length && u < 0.3 ? (u < 0.15 ? 1.52 : 1.55) : (u < 0.6 ? 1.9 : 1.7);
        if (!side_atom(anchor, radius)) break;
        anchor = atoms.size() - 1;
      }
    }
  }
  atoms.resize(std::min<std::size_t>(atoms.size(), n));
  return atoms;
}

void proteins(Suite& s) {
  const int sizes[] = {10, 18, 30, 45, 65, 90, 130, 200};
  for (int n : sizes)
    for (double probe : kProbes) {
      StressCase c = s.begin("protein", "n" + std::to_string(n) + "/probe" + num(probe));
      Rng rng(c.seed);
      c.probe = probe;
      c.atoms = pseudo_protein(n, rng);
      c.note = "self-avoiding N-CA-C chain, 1.5 Å bonds, side atoms";
      s.add(std::move(c));
    }
}

// Lattices -----------------------------------------------------------------------------

/// Simple cubic lattice of m x m x m points, spacing a (Å).
std::vector<Vec3> sc_points(int m, double a) {
  std::vector<Vec3> p;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < m; ++j)
      for (int k = 0; k < m; ++k) p.push_back(a * Vec3(i, j, k));
  return p;
}

/// Face-centred cubic lattice: c x c x c conventional cells of edge a (Å),
/// the points (i, j, k) a / 2 with i + j + k even, 0 <= i, j, k <= 2c.
std::vector<Vec3> fcc_points(int c, double a) {
  std::vector<Vec3> p;
  for (int i = 0; i <= 2 * c; ++i)
    for (int j = 0; j <= 2 * c; ++j)
      for (int k = 0; k <= 2 * c; ++k)
        if ((i + j + k) % 2 == 0) p.push_back(0.5 * a * Vec3(i, j, k));
  return p;
}

/// Body-centred cubic lattice: the (c+1)³ cell corners and c³ cell centres
/// of c x c x c cells of edge a (Å).
std::vector<Vec3> bcc_points(int c, double a) {
  std::vector<Vec3> p = sc_points(c + 1, a);
  for (int i = 0; i < c; ++i)
    for (int j = 0; j < c; ++j)
      for (int k = 0; k < c; ++k) p.push_back(a * Vec3(i + 0.5, j + 0.5, k + 0.5));
  return p;
}

struct Regime {
  std::string name;
  double spacing;  ///< Å
  bool singular;
  std::string note;
};

void add_lattice(Suite& s, const std::string& kind, int size, double r, double probe, const Regime& g,
                 const std::vector<Vec3>& pts) {
  StressCase c = s.begin("lattice", kind + std::to_string(size) + "/" + g.name + "/r" + num(r));
  c.probe = probe;
  for (const Vec3& x : pts) c.atoms.push_back({x, r});
  c.singular = g.singular;
  char buf[64];
  std::snprintf(buf, sizeof buf, "spacing %.17g Å; ", g.spacing);
  c.note = buf + g.note;
  s.add(std::move(c));
}

void lattices(Suite& s) {
  // Probe cycling for the non-exact regimes; exact ones use dyadic r + p.
  int turn = 0;
  auto next_probe = [&]() { return kProbes[turn++ % 4]; };
  const double deltas[] = {1e-3, 1e-4, 1e-6};

  // Simple cubic. Thresholds with t = r + p, R = sqrt(2) t: edge tangency
  // a = 2R; square centre covered iff a <= 2t (exact in floating point);
  // cube centre covered iff a <= 2R / sqrt(3).
  {
    const double r = 1.5;
    auto regimes = [&](double p) {
      const double t = r + p, R = unshrunk(r, p);
      std::vector<Regime> g = {
          {"apart", 2 * R + 0.3, false, "isolated balls (gap 0.3 Å)"},
          {"edge-touch", 2 * R, true, "neighbours tangent (up to rounding of R)"},
          {"frame", 1.7 * R, false, "edges overlap, square holes open"},
          {"face-exact", 2 * t, true, "square centres exactly on all four balls (exact)"},
          {"voids", 1.85 * t, false, "squares closed, a void in every cube"},
          {"cube-touch", 2 * R / std::sqrt(3.0), true, "cube centres on the balls (up to rounding): voids closing"},
          {"solid", 1.3 * t, false, "everything covered"},
      };
      for (double d : deltas) {
        g.push_back({"edge-gap" + num(d), 2 * R + d, false, "neighbours " + num(d) + " Å apart"});
        g.push_back({"edge-overlap" + num(d), 2 * R - d, false, "neighbours overlapping by " + num(d) + " Å"});
      }
      for (double d : {1e-3, 1e-6}) {
        g.push_back({"face-open" + num(d), 2 * t + d, false, "square holes just open"});
        g.push_back({"face-closed" + num(d), 2 * t - d, false, "square holes just closed"});
      }
      g.push_back({"cube-open1e-4", 2 * R / std::sqrt(3.0) + 1e-4, false, "voids just open"});
      g.push_back({"cube-closed1e-4", 2 * R / std::sqrt(3.0) - 1e-4, false, "voids just closed"});
      return g;
    };
    const double exact_probes[] = {0.0, 0.5, 3.0};
    int e = 0;
    for (int m : {2, 3}) {
      for (const Regime& g0 : regimes(0.0)) {
        // Exact regimes need a dyadic r + p; the others cycle all probes.
        const bool exact = g0.name == "face-exact";
        const double p = exact ? exact_probes[e++ % 3] : next_probe();
        if (m == 3 && (g0.name.find(num(1e-6)) != std::string::npos || g0.name.find(num(1e-3)) != std::string::npos))
          continue;  // the 3x3x3 lattice only at the coarse and 1e-4 thresholds
        for (const Regime& g : regimes(p))
          if (g.name == g0.name) add_lattice(s, "sc", m, r, p, g, sc_points(m, g.spacing));
      }
    }
    for (const char* name : {"frame", "voids", "face-exact"}) {
      const double p = std::string(name) == "face-exact" ? 0.5 : next_probe();
      for (const Regime& g : regimes(p))
        if (g.name == name) add_lattice(s, "sc", 4, r, p, g, sc_points(4, g.spacing));
    }
  }

  // Face-centred cubic, cube edge a, nearest neighbours a / sqrt(2) apart:
  // tangent iff a = 4t (exact); triangles covered iff a <= 2 sqrt(3) t,
  // tetrahedral sites iff a <= 4 sqrt(2/3) t, octahedral sites iff a <= 2 sqrt(2) t.
  {
    const double r = 1.75;
    for (int c : {1, 2}) {
      auto regimes = [&](double p) {
        const double t = r + p, R = unshrunk(r, p);
        std::vector<Regime> g = {
            {"apart", 4.4 * t, false, "isolated balls"},
            {"nn-touch-exact", 4 * t, true, "nearest neighbours exactly tangent"},
            {"network", 3.7 * t, false, "edges overlap, triangles open"},
            {"tet-voids", 3.3 * t, false, "triangles closed, tetrahedral and octahedral voids"},
            {"oct-voids", 3.0 * t, false, "tetrahedral sites covered, octahedral voids"},
            {"solid", 2.6 * t, false, "everything covered"},
        };
        for (double d : {1e-4, 1e-6}) {
          g.push_back({"nn-gap" + num(d), std::sqrt(2.0) * (2 * R + d), false, "neighbours " + num(d) + " Å apart"});
          g.push_back({"nn-overlap" + num(d), std::sqrt(2.0) * (2 * R - d), false,
                       "neighbours overlapping by " + num(d) + " Å"});
        }
        return g;
      };
      for (const Regime& g0 : regimes(0.0)) {
        const bool exact = g0.name == "nn-touch-exact";
        const double p = exact ? (c == 1 ? 0.0 : 0.5) : next_probe();
        if (c == 2 && g0.name.find(num(1e-6)) != std::string::npos) continue;
        for (const Regime& g : regimes(p))
          if (g.name == g0.name) add_lattice(s, "fcc", c, r, p, g, fcc_points(c, g.spacing));
      }
    }
  }

  // Body-centred cubic, cube edge a, nearest neighbours sqrt(3) a / 2 apart:
  // tangent iff a = 4R / sqrt(3) (irrational: singular up to rounding).
  {
    const double r = 1.625;
    for (int c : {1, 2}) {
      auto regimes = [&](double p) {
        const double R = unshrunk(r, p), a0 = 4 * R / std::sqrt(3.0);
        std::vector<Regime> g = {
            {"apart", 1.1 * a0, false, "isolated balls"},
            {"nn-touch", a0, true, "nearest neighbours tangent (up to rounding)"},
            {"f0.9", 0.9 * a0, false, "a = 0.9 x tangency"},
            {"f0.8", 0.8 * a0, false, "a = 0.8 x tangency"},
            {"f0.7", 0.7 * a0, false, "a = 0.7 x tangency"},
            {"f0.6", 0.6 * a0, false, "a = 0.6 x tangency"},
            {"nn-gap1e-4", (2 * R + 1e-4) * 2 / std::sqrt(3.0), false, "neighbours 1e-4 Å apart"},
            {"nn-overlap1e-4", (2 * R - 1e-4) * 2 / std::sqrt(3.0), false, "neighbours overlapping by 1e-4 Å"},
        };
        return g;
      };
      for (const Regime& g0 : regimes(0.0)) {
        const double p = next_probe();
        for (const Regime& g : regimes(p))
          if (g.name == g0.name) add_lattice(s, "bcc", c, r, p, g, bcc_points(c, g.spacing));
      }
    }
    for (double f : {0.8, 0.7}) {  // 3 x 3 x 3 cells (91 atoms)
      const double p = next_probe();
      const double a = f * 4 * unshrunk(r, p) / std::sqrt(3.0);
      add_lattice(s, "bcc", 3, r, p, {"f" + num(f), a, false, "a = " + num(f) + " x tangency"}, bcc_points(3, a));
    }
  }
}

// Nested shells ("onions") ----------------------------------------------------------------

/// One shell: radius and neighbour spacing, both in units of the unshrunk
/// ball radius R; the number of atoms n = 8 pi (rs/R)² / (sqrt(3) f²) gives a
/// triangular packing of edge about f R (closed for f < sqrt(3)).
struct Shell {
  double radius;
  double spacing;
};

void shells(Suite& s) {
  const struct {
    const char* name;
    std::vector<Shell> shells;
    bool centre_atom;
    const char* note;
  } configs[] = {
      {"closed1", {{2.2, 1.3}}, false, "one closed shell: a cavity"},
      {"porous1", {{2.2, 1.8}}, false, "one porous shell: tunnels"},
      {"beads1", {{2.5, 2.4}}, false, "beads on a sphere"},
      {"onion2", {{1.6, 1.3}, {4.0, 1.3}}, false, "two closed shells: two cavities"},
      {"onion2-porous", {{1.6, 1.3}, {4.0, 1.8}}, false, "closed inner shell, porous outer shell"},
      {"onion3", {{1.3, 1.3}, {3.5, 1.8}, {5.7, 2.4}}, false, "closed, porous and beaded shells"},
      {"centre-shell", {{2.6, 1.3}}, true, "an atom inside a closed shell"},
  };
  const double probes[2][7] = {{0.0, 0.5, 1.4, 3.0, 0.0, 0.5, 1.4}, {1.4, 3.0, 0.0, 0.5, 1.4, 3.0, 0.5}};
  for (int variant = 0; variant < 2; ++variant)
    for (std::size_t k = 0; k < std::size(configs); ++k) {
      const auto& cfg = configs[k];
      StressCase c = s.begin("shell", std::string(cfg.name) + "/v" + std::to_string(variant));
      Rng rng(c.seed);
      c.probe = probes[variant][k];
      const double r = 1.6;
      const double R = unshrunk(r, c.probe);
      if (cfg.centre_atom) c.atoms.push_back({Vec3::Zero(), r});
      for (const Shell& sh : cfg.shells) {
        const int n =
            static_cast<int>(std::lround(8 * kPi * sh.radius * sh.radius / (std::sqrt(3.0) * sh.spacing * sh.spacing)));
        for (const Vec3& x : sphere_points(n, sh.radius * R, rng))
          c.atoms.push_back({x, variant == 0 ? r : r + rng.uniform(-0.1, 0.1)});
      }
      c.note = cfg.note;
      s.add(std::move(c));
    }
}

// Rings, helices, a knot ------------------------------------------------------------------

/// n atoms of radius r on a circle of radius rc (Å) in the xy plane.
std::vector<StressAtom> ring(int n, double rc, double r) {
  std::vector<StressAtom> atoms;
  for (int i = 0; i < n; ++i) {
    const double phi = 2 * kPi * i / n;
    atoms.push_back({rc * Vec3(std::cos(phi), std::sin(phi), 0), r});
  }
  return atoms;
}

void rings(Suite& s) {
  int turn = 0;
  auto next_probe = [&]() { return kProbes[turn++ % 4]; };
  const double r = 1.7;
  auto add = [&](const std::string& key, double p, std::vector<StressAtom> atoms, bool singular,
                 const std::string& note) { s.add("ring", key, p, std::move(atoms), singular, note); };
  for (int n : {5, 8, 12, 20, 30}) {  // tori: neighbours 1.5 R apart, hole open
    const double p = next_probe(), R = unshrunk(r, p);
    add("torus/n" + std::to_string(n), p, ring(n, 1.5 * R / (2 * std::sin(kPi / n)), r), false,
        "neighbours 1.5 R apart: a torus");
  }
  for (int n : {6, 12}) {  // separate beads
    const double p = next_probe(), R = unshrunk(r, p);
    add("beads/n" + std::to_string(n), p, ring(n, 2.2 * R / (2 * std::sin(kPi / n)), r), false,
        "neighbours 2.2 R apart: separate balls");
  }
  for (double d : {1e-3, 1e-6}) {  // hexagon whose hole is just open / closed
    const double p = next_probe(), R = unshrunk(r, p);
    add("hole-open" + num(d) + "/n6", p, ring(6, R + d, r), false, "ring radius R + " + num(d) + " Å: hole just open");
    add("hole-closed" + num(d) + "/n6", p, ring(6, R - d, r), false,
        "ring radius R - " + num(d) + " Å: hole just closed");
  }
  {
    const double p = next_probe(), R = unshrunk(r, p);
    add("hole-touch/n6", p, ring(6, R, r), true, "ring radius R: hole closing (up to rounding)");
  }
  {  // a square ring (±t, ±t, 0): the hole closes exactly at its centre
    const double rr = 1.5, p = 0.5, t = rr + p;
    std::vector<StressAtom> atoms = {
        {Vec3(t, t, 0), rr}, {Vec3(-t, t, 0), rr}, {Vec3(-t, -t, 0), rr}, {Vec3(t, -t, 0), rr}};
    add("hole-exact/n4", p, atoms, true, "square ring: centre exactly on the four balls (exact)");
  }
  for (double sign : {1.0, -1.0}) {  // octagon of beads just touching / apart
    const double p = next_probe(), R = unshrunk(r, p);
    const double spacing = 2 * R + sign * 1e-4;
    add(std::string(sign > 0 ? "neck-gap" : "neck-overlap") + "1e-4/n8", p,
        ring(8, spacing / (2 * std::sin(kPi / 8)), r), false,
        std::string("neighbours ") + (sign > 0 ? "1e-4 Å apart" : "overlapping by 1e-4 Å"));
  }
}

void helices(Suite& s) {
  int turn = 1;
  auto next_probe = [&]() { return kProbes[turn++ % 4]; };
  auto add = [&](const std::string& key, double p, std::vector<StressAtom> atoms, const std::string& note) {
    s.add("helix", key, p, std::move(atoms), false, note);
  };
  for (int n : {20, 40, 80}) {  // alpha-helix-like rod
    std::vector<StressAtom> atoms;
    for (int i = 0; i < n; ++i) {
      const double phi = i * 100.0 * kPi / 180.0;
      atoms.push_back({Vec3(2.3 * std::cos(phi), 2.3 * std::sin(phi), 1.5 * i), 1.7});
    }
    add("alpha/n" + std::to_string(n), next_probe(), atoms, "radius 2.3 Å, 100°/atom, rise 1.5 Å/atom");
  }
  const double r = 1.6;
  const struct {
    const char* name;
    int n;
    double pitch;  ///< per turn, in units of R
  } springs[] = {{"spring", 30, 2.4}, {"spring", 60, 2.4}, {"spring-tight", 48, 1.5}};
  for (const auto& sp : springs) {  // coil of radius 3R, 12 atoms per turn
    const double p = next_probe(), R = unshrunk(r, p);
    std::vector<StressAtom> atoms;
    for (int i = 0; i < sp.n; ++i) {
      const double phi = 2 * kPi * i / 12;
      atoms.push_back({Vec3(3 * R * std::cos(phi), 3 * R * std::sin(phi), sp.pitch * R * i / 12), r});
    }
    add(std::string(sp.name) + "/n" + std::to_string(sp.n), p, atoms,
        "coil of radius 3R, pitch " + num(sp.pitch) + " R per turn");
  }
  for (int n : {48, 90}) {  // trefoil knot, neighbours 1.4 R apart along the curve
    const double p = next_probe(), R = unshrunk(r, p);
    auto curve = [](double u) {
      return Vec3(std::sin(u) + 2 * std::sin(2 * u), std::cos(u) - 2 * std::cos(2 * u), -std::sin(3 * u));
    };
    double length = 0;
    constexpr int kSteps = 20000;
    for (int k = 0; k < kSteps; ++k) length += (curve(2 * kPi * (k + 1) / kSteps) - curve(2 * kPi * k / kSteps)).norm();
    const double scale = 1.4 * R * n / length;
    // Equal arc-length samples.
    std::vector<StressAtom> atoms;
    double walked = 0, next = 0;
    for (int k = 0; k < kSteps && static_cast<int>(atoms.size()) < n; ++k) {
      const Vec3 a = curve(2 * kPi * k / kSteps), b = curve(2 * kPi * (k + 1) / kSteps);
      const double seg = (b - a).norm();
      while (next <= walked + seg && static_cast<int>(atoms.size()) < n) {
        atoms.push_back({scale * (a + (b - a) * ((next - walked) / seg)), r});
        next += length / n;
      }
      walked += seg;
    }
    add("trefoil/n" + std::to_string(n), p, atoms, "trefoil knot, neighbours 1.4 R apart: a knotted torus");
  }
}

// Near-threshold and exactly singular configurations -------------------------------------

void thresholds(Suite& s) {
  int turn = 2;
  auto next_probe = [&]() { return kProbes[turn++ % 4]; };
  auto add = [&](const std::string& key, double p, std::vector<StressAtom> atoms, bool singular,
                 const std::string& note) { s.add("threshold", key, p, std::move(atoms), singular, note); };
  // Pairs whose unshrunk balls are |d| apart (d > 0) or overlap by |d| (d < 0):
  // a thin gap or a thin neck of the skin.
  const double radii[3][2] = {{1.5, 1.5}, {1.5, 1.9}, {1.7, 1.52}};
  for (const auto& rr : radii)
    for (double d : {1e-3, -1e-3, 1e-4, -1e-4, 1e-6, -1e-6, 1e-2, -1e-2}) {
      if (std::abs(d) == 1e-2 && rr[0] != rr[1]) continue;
      const std::string key =
          std::string("pair/") + (d > 0 ? "gap" : "overlap") + num(std::abs(d)) + "/r" + num(rr[0]) + "-" + num(rr[1]);
      StressCase probe_seed = s.begin("threshold", key);
      Rng rng(probe_seed.seed);
      const double p = next_probe();
      const double dist = unshrunk(rr[0], p) + unshrunk(rr[1], p) + d;
      add(key, p, {{Vec3::Zero(), rr[0]}, {dist * rng.unit_vector(), rr[1]}}, false,
          d > 0 ? "unshrunk balls " + num(d) + " Å apart" : "unshrunk balls overlapping by " + num(-d) + " Å");
    }
  // Exactly tangent pairs: offset (u, u, 0) with u = r1 + r2 + 2p, so that
  // |offset|² = 2 u² = (R1 + R2)² exactly when r + p is dyadic.
  const double tangent[4][3] = {{1.5, 1.5, 0.0}, {1.5, 1.75, 0.5}, {1.625, 1.875, 3.0}, {1.5, 1.5, 1.4}};
  for (const auto& tg : tangent) {
    const double u = tg[0] + tg[1] + 2 * tg[2];
    add("pair-tangent/r" + num(tg[0]) + "-" + num(tg[1]), tg[2], {{Vec3::Zero(), tg[0]}, {Vec3(u, u, 0), tg[1]}}, true,
        tg[2] == 1.4 ? "unshrunk balls tangent up to rounding" : "unshrunk balls exactly tangent");
  }
  // Three equal balls on an equilateral triangle of circumradius R ± d: the
  // hole of the three-ball ring just open (torus) or just closed (sphere).
  // Four equal balls on a regular tetrahedron of circumradius R ± d: a void
  // just open or just closed.
  for (double d : {1e-3, -1e-3, 1e-4, -1e-4, 1e-6, -1e-6}) {
    const double r = 1.7;
    {
      const double p = next_probe(), rc = unshrunk(r, p) + d;
      add(std::string("triangle-hole/") + (d > 0 ? "open" : "closed") + num(std::abs(d)), p, ring(3, rc, r), false,
          "three-ball ring, circumradius R " + std::string(d > 0 ? "+ " : "- ") + num(std::abs(d)) + " Å");
    }
    {
      const double p = next_probe(), rc = unshrunk(r, p) + d;
      const double k = rc / std::sqrt(3.0);
      std::vector<StressAtom> atoms = {
          {k * Vec3(1, 1, 1), r}, {k * Vec3(1, -1, -1), r}, {k * Vec3(-1, 1, -1), r}, {k * Vec3(-1, -1, 1), r}};
      add(std::string("tet-void/") + (d > 0 ? "open" : "closed") + num(std::abs(d)), p, atoms, false,
          "regular tetrahedron, circumradius R " + std::string(d > 0 ? "+ " : "- ") + num(std::abs(d)) + " Å");
    }
  }
  {  // right isosceles triangle, legs 2t: hypotenuse pair tangent, orthocentre on all three balls (exact)
    const double r = 1.5, p = 0.5, t = r + p;
    add("triangle-exact", p, {{Vec3::Zero(), r}, {Vec3(2 * t, 0, 0), r}, {Vec3(0, 2 * t, 0), r}}, true,
        "right isosceles triangle of legs 2t: exactly singular");
  }
  {  // tetrahedron inscribed in the sphere of radius R about the origin: void closing exactly
    const double r = 1.5, p = 0.5, t = r + p;
    add("tet-exact", p, {{Vec3(t, t, 0), r}, {Vec3(-t, t, 0), r}, {Vec3(0, -t, t), r}, {Vec3(0, -t, -t), r}}, true,
        "tetrahedron with orthocentre exactly on its four balls (exact)");
  }
}

// Duplicate and nested atoms -----------------------------------------------------------------

void duplicates(Suite& s) {
  int turn = 3;
  auto next_probe = [&]() { return kProbes[turn++ % 4]; };
  auto cluster = [](int n, Rng& rng) {
    std::vector<StressAtom> atoms;
    const double side = std::cbrt(n * 4.0 / 3.0 * kPi * 1.6 * 1.6 * 1.6 / 0.12);
    for (int i = 0; i < n; ++i)
      atoms.push_back({Vec3(rng.uniform(0, side), rng.uniform(0, side), rng.uniform(0, side)), rng.uniform(1.3, 1.9)});
    return atoms;
  };
  auto add = [&](StressCase c, const std::string& note, bool singular = false) {
    c.note = note;
    c.singular = singular;
    s.add(std::move(c));
  };
  for (int n : {10, 30, 60}) {  // exact copies of every fifth atom
    StressCase c = s.begin("duplicate", "exact/n" + std::to_string(n));
    Rng rng(c.seed);
    c.probe = next_probe();
    c.atoms = cluster(n, rng);
    for (int i = 0; i < n; i += 5) c.atoms.push_back(c.atoms[i]);
    add(std::move(c), "every fifth atom listed twice");
  }
  {
    StressCase c = s.begin("duplicate", "all-same/n5");
    c.probe = next_probe();
    c.atoms.assign(5, {Vec3(1.25, -0.5, 2.0), 1.7});
    add(std::move(c), "five copies of one atom");
  }
  {
    StressCase c = s.begin("duplicate", "pair-twice");
    c.probe = next_probe();
    c.atoms = {{Vec3::Zero(), 1.6}, {Vec3(2.5, 0.4, 0.1), 1.7}, {Vec3::Zero(), 1.6}, {Vec3(2.5, 0.4, 0.1), 1.7}};
    add(std::move(c), "two overlapping atoms, each listed twice");
  }
  for (int n : {10, 30}) {  // concentric smaller copies (redundant weighted points)
    StressCase c = s.begin("duplicate", "concentric-smaller/n" + std::to_string(n));
    Rng rng(c.seed);
    c.probe = next_probe();
    c.atoms = cluster(n, rng);
    for (int i = 0; i < n; i += 5) c.atoms.push_back({c.atoms[i].centre, c.atoms[i].radius - 0.4});
    add(std::move(c), "every fifth atom with a concentric copy 0.4 Å smaller");
  }
  {
    StressCase c = s.begin("duplicate", "concentric-bigger/n12");
    Rng rng(c.seed);
    c.probe = next_probe();
    c.atoms = cluster(12, rng);
    for (int i = 0; i < 12; i += 3) c.atoms.push_back({c.atoms[i].centre, c.atoms[i].radius + 0.3});
    add(std::move(c), "every third atom with a concentric copy 0.3 Å bigger (the first becomes redundant)");
  }
  for (int n : {10, 30}) {  // small atoms strictly inside bigger ones, off centre
    StressCase c = s.begin("duplicate", "nested/n" + std::to_string(n));
    Rng rng(c.seed);
    c.probe = next_probe();
    c.atoms = cluster(n, rng);
    for (int i = 0; i < n; i += 4) {
      const double rs = 0.6;
      const double room = unshrunk(c.atoms[i].radius, c.probe) - unshrunk(rs, c.probe);
      c.atoms.push_back({c.atoms[i].centre + 0.5 * room * rng.unit_vector(), rs});
    }
    add(std::move(c), "every fourth atom holds a 0.6 Å atom halfway to internal tangency");
  }
  {  // internally tangent: offset (d, d, 0), d = t_big - t_small, |offset| = R_big - R_small exactly
    StressCase c = s.begin("duplicate", "nested-tangent");
    c.probe = 0.5;
    const double rb = 1.75, rs = 0.75;
    const double d = rb - rs;
    c.atoms = {{Vec3::Zero(), rb}, {Vec3(d, d, 0), rs}, {Vec3(3.5, -0.5, 0.25), 1.5}};
    add(std::move(c), "a small ball internally tangent to a big one (exact)", true);
  }
  {
    StressCase c = s.begin("duplicate", "near-copies/n10");
    Rng rng(c.seed);
    c.probe = next_probe();
    c.atoms = cluster(10, rng);
    for (int i = 0; i < 10; i += 3)
      c.atoms.push_back({c.atoms[i].centre + 1e-9 * rng.unit_vector(), c.atoms[i].radius});
    add(std::move(c), "copies of every third atom moved by 1e-9 Å");
  }
  {
    StressCase c = s.begin("duplicate", "lattice-twice/sc2");
    c.probe = next_probe();
    const double R = unshrunk(1.5, c.probe);
    for (const Vec3& x : sc_points(2, 1.7 * R)) c.atoms.push_back({x, 1.5});
    const std::size_t n = c.atoms.size();
    for (std::size_t i = 0; i < n; ++i) c.atoms.push_back(c.atoms[i]);
    add(std::move(c), "a 2x2x2 simple cubic frame, every atom listed twice");
  }
}

/// Appends a rotated and translated twin of every second case of each family.
// The fallback's families: membranes, cages in shells, dense packings, channels ------------------------

/// Height directions per geometry of the fallback's families. [measured]
/// The height direction decides where the fronts meet: a molecule that meshes
/// in one direction may tangle in another.
constexpr int kDirectionsPerGeometry = 6;

/// Adds `c` swept in `count` random directions ("/dK"); every third of them
/// is also rotated and translated.
void add_directions(Suite& s, const StressCase& base, int count = kDirectionsPerGeometry) {
  for (int k = 0; k < count; ++k) {
    StressCase c = base;
    c.name += "/d" + std::to_string(k);
    c.seed = case_seed(s.seed, c.name);
    Rng rng(c.seed);
    c.direction = rng.unit_vector();
    char buf[96];
    std::snprintf(buf, sizeof buf, "; height direction (%.3f, %.3f, %.3f)", c.direction.x(), c.direction.y(),
                  c.direction.z());
    c.note += buf;
    if (k % 3 == 2) c = rotated_translated(c, rng);
    s.cases.push_back(std::move(c));
  }
}

/// A patch of a lipid bilayer: n x n lipids per leaflet, 8 Å apart (jittered),
/// each a head group of four atoms and two zigzag tails of `tail` carbons
/// (1.27 Å steps, slightly tilted); the leaflets' tails meet in the middle.
std::vector<StressAtom> bilayer(int n, int tail, Rng& rng) {
  std::vector<StressAtom> atoms;
  const double spacing = 8.0, step = 1.27;
  const struct {
    double dx, dy, dz, r;
  } head[] = {{0, 0, 3.0, 1.8}, {1.5, 0.5, 1.6, 1.9}, {-1.2, 0.8, 0.4, 1.52}, {0.3, -0.9, -0.9, 1.52}};
  for (const double side : {1.0, -1.0})
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const double x0 = i * spacing + rng.uniform(-1, 1), y0 = j * spacing + rng.uniform(-1, 1);
        const double ztop = side * (tail * step + 6.0) + rng.uniform(-0.8, 0.8);
        for (const auto& h : head) atoms.push_back({Vec3(x0 + h.dx, y0 + h.dy, ztop + side * h.dz), h.r});
        for (const double ox : {-2.2, 2.2}) {
          const double tx = rng.uniform(-0.15, 0.15), ty = rng.uniform(-0.15, 0.15);
          double z = ztop - side * 1.5;
          for (int c = 0; c < tail; ++c, z -= side * step)
            atoms.push_back({Vec3(x0 + ox + (c % 2 ? 0.42 : -0.42) + tx * c, y0 + ty * c, z), 1.7});
        }
      }
  return atoms;
}

void membranes(Suite& s) {
  for (const int n : {2, 3})
    for (const double p : kProbes) {
      StressCase c = s.begin("membrane", "bilayer" + std::to_string(n) + "x" + std::to_string(n));
      Rng rng(c.seed);
      c.probe = p;
      c.atoms = bilayer(n, 10, rng);
      c.note = "two leaflets of " + std::to_string(n * n) + " lipid-like chains";
      c.name += "/p" + num(p);
      add_directions(s, c);
    }
}

/// The 12 vertices of an icosahedron on the unit sphere.
std::vector<Vec3> icosahedron() {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> v;
  for (const double a : {-1.0, 1.0})
    for (const double b : {-g, g}) {
      v.push_back(Vec3(0, a, b).normalized());
      v.push_back(Vec3(a, b, 0).normalized());
      v.push_back(Vec3(b, 0, a).normalized());
    }
  return v;
}

/// Points of a class-I geodesic sphere of frequency f and radius rs:
/// 10 f² + 2 of them (each icosahedron face split into f² triangles, projected).
std::vector<Vec3> geodesic_sphere(int f, double rs) {
  const std::vector<Vec3> v = icosahedron();
  double edge = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t j = i + 1; j < v.size(); ++j) edge = std::min(edge, (v[i] - v[j]).norm());
  auto is_edge = [&](std::size_t i, std::size_t j) { return std::abs((v[i] - v[j]).norm() - edge) < 1e-9; };
  std::vector<Vec3> pts;
  auto add = [&](const Vec3& x) {
    for (const Vec3& q : pts)
      if ((q - x).norm() < 1e-9 * rs) return;
    pts.push_back(x);
  };
  for (std::size_t i = 0; i < v.size(); ++i)
    for (std::size_t j = i + 1; j < v.size(); ++j)
      for (std::size_t k = j + 1; k < v.size(); ++k) {
        if (!is_edge(i, j) || !is_edge(j, k) || !is_edge(i, k)) continue;
        for (int a = 0; a <= f; ++a)
          for (int b = 0; a + b <= f; ++b) add(rs * (a * v[i] + b * v[j] + (f - a - b) * v[k]).normalized());
      }
  return pts;
}

/// The 60 vertices of a truncated icosahedron (a C60 cage) of circumradius rc:
/// the cyclic permutations of (0, ±1, ±3g), (±1, ±(2 + g), ±2g), (±g, ±2, ±g³).
std::vector<Vec3> truncated_icosahedron(double rc) {
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> pts;
  for (const Vec3& b : {Vec3(0, 1, 3 * g), Vec3(1, 2 + g, 2 * g), Vec3(g, 2, g * g * g)})
    for (int perm = 0; perm < 3; ++perm) {
      const Vec3 q(b[perm], b[(perm + 1) % 3], b[(perm + 2) % 3]);
      for (int signs = 0; signs < 8; ++signs) {
        const Vec3 x(signs & 1 ? -q.x() : q.x(), signs & 2 ? -q.y() : q.y(), signs & 4 ? -q.z() : q.z());
        bool seen = false;
        for (const Vec3& y : pts) seen |= (x - y).norm() < 1e-12;
        if (!seen) pts.push_back(x);
      }
    }
  for (Vec3& x : pts) x *= rc / x.norm();
  return pts;
}

void cages(Suite& s) {
  const struct {
    const char* name;
    double cage_radius;
    int frequency;
    double shell_radius;
  } configs[] = {{"c60-in-geodesic6", 8.7, 6, 20.0}, {"c60-in-geodesic5", 6.5, 5, 16.0}};
  for (const auto& cfg : configs)
    for (const double p : kProbes) {
      StressCase c = s.begin("cage", cfg.name);
      c.probe = p;
      for (const Vec3& x : truncated_icosahedron(cfg.cage_radius)) c.atoms.push_back({x, 1.7});
      for (const Vec3& x : geodesic_sphere(cfg.frequency, cfg.shell_radius)) c.atoms.push_back({x, 1.7});
      c.note = "a C60-like cage of radius " + num(cfg.cage_radius) + " Å inside a geodesic shell of radius " +
               num(cfg.shell_radius) + " Å";
      c.name += "/p" + num(p);
      add_directions(s, c);
    }
}

/// n atoms uniform in a ball whose radius gives a van der Waals packing
/// fraction `fraction`, with no clash removed (a low-resolution model's
/// overlapping atoms); radii uniform in [1.5, 2.0] Å.
std::vector<StressAtom> dense_packing(int n, double fraction, Rng& rng) {
  const double rb = std::cbrt(n * 1.75 * 1.75 * 1.75 / fraction);
  std::vector<StressAtom> atoms;
  while (static_cast<int>(atoms.size()) < n) {
    const Vec3 x(rng.uniform(-rb, rb), rng.uniform(-rb, rb), rng.uniform(-rb, rb));
    if (x.norm() <= rb) atoms.push_back({x, rng.uniform(1.5, 2.0)});
  }
  return atoms;
}

void packings(Suite& s) {
  for (const int n : {200, 400})
    for (const double p : kProbes) {
      StressCase c = s.begin("packing", "dense" + std::to_string(n));
      Rng rng(c.seed);
      c.probe = p;
      c.atoms = dense_packing(n, 0.65, rng);
      c.note = std::to_string(n) + " atoms at packing fraction 0.65, clashes kept";
      c.name += "/p" + num(p);
      add_directions(s, c);
    }
}

void channels(Suite& s) {
  const struct {
    const char* name;
    int per_ring, rings;
    double ring_radius, rise;
  } configs[] = {{"narrow", 8, 10, 4.6, 2.6}, {"wide", 11, 14, 6.4, 2.8}};
  for (const auto& cfg : configs)
    for (const double p : kProbes) {
      StressCase c = s.begin("channel", cfg.name);
      Rng rng(c.seed);
      c.probe = p;
      for (int k = 0; k < cfg.rings; ++k)
        for (int i = 0; i < cfg.per_ring; ++i) {
          const double phi = 2 * kPi * (i + 0.5 * (k % 2)) / cfg.per_ring;
          const double rr = cfg.ring_radius + rng.uniform(-0.2, 0.2);
          c.atoms.push_back({Vec3(rr * std::cos(phi), rr * std::sin(phi), k * cfg.rise), rng.uniform(1.6, 1.8)});
        }
      c.note = "a tube of " + std::to_string(cfg.rings) + " rings of " + std::to_string(cfg.per_ring) +
               " atoms, radius " + num(cfg.ring_radius) + " Å: a channel or a pore";
      c.name += "/p" + num(p);
      add_directions(s, c);
    }
}

// The low-resolution class: all-atom models with the clashes of 4 Å structures --------------------

/// Height directions per low-resolution geometry: the front meets itself
/// where the direction puts the fronts, so each model is swept in many.
constexpr int kLowResDirections = 20;

/// The protein atoms of a bundled molecule (data/`file`), hydrogens and
/// waters dropped by the reader, with the residue each atom belongs to and
/// whether it is a side-chain atom (not N, CA, C, O or OXT).
struct ModelAtoms {
  std::vector<StressAtom> atoms;
  std::vector<int> residue;
  std::vector<bool> side_chain;
};

ModelAtoms bundled_model(const std::string& file) {
  skin::ReadOptions ro;
  ro.keep_hydrogens = false;
  const skin::Molecule mol = skin::read_molecule(std::string(SKINMESH_DATA) + "/" + file, ro);
  ModelAtoms m;
  int residue = -1;
  std::string last;
  for (const skin::Atom& a : mol.atoms) {
    const std::string key = a.chain + "/" + std::to_string(a.residue_number) + a.insertion_code;
    if (key != last) ++residue, last = key;
    m.atoms.push_back({a.centre, a.radius});
    m.residue.push_back(residue);
    m.side_chain.push_back(a.name != "N" && a.name != "CA" && a.name != "C" && a.name != "O" && a.name != "OXT");
  }
  return m;
}

/// Misplaced side chains, as a model built into 4 Å density has them: each
/// residue's side chain moved rigidly by a random vector of length uniform in
/// [0.5, 1.5] Å, then every atom by Gaussian noise of 0.2 Å; clashes kept.
std::vector<StressAtom> displaced_side_chains(const ModelAtoms& m, Rng& rng) {
  std::vector<Vec3> shift;
  for (std::size_t i = 0; i < m.atoms.size(); ++i)
    if (static_cast<std::size_t>(m.residue[i]) >= shift.size())
      shift.push_back(rng.uniform(0.5, 1.5) * rng.unit_vector());
  std::vector<StressAtom> atoms = m.atoms;
  for (std::size_t i = 0; i < atoms.size(); ++i) {
    if (m.side_chain[i]) atoms[i].centre += shift[m.residue[i]];
    atoms[i].centre += 0.2 * Vec3(rng.normal(), rng.normal(), rng.normal());
  }
  return atoms;
}

/// Two copies of `a` packed tighter than van der Waals contact: the second is
/// the first turned half a turn about a random axis, pushed into the first
/// until the closest pair of atoms of the two copies is `closest` Å apart
/// (contact is about 3.4 Å), then every atom moved by Gaussian noise of 0.3 Å.
std::vector<StressAtom> packed_dimer(const std::vector<StressAtom>& a, double closest, Rng& rng) {
  Vec3 centre = Vec3::Zero();
  for (const StressAtom& x : a) centre += x.centre;
  centre /= static_cast<double>(a.size());
  const Vec3 u = rng.unit_vector();
  const Vec3 axis = u.unitOrthogonal();
  auto partner = [&](double offset) {
    const Vec3 point = centre + offset * u;
    std::vector<StressAtom> b = a;
    for (StressAtom& x : b) {
      const Vec3 d = x.centre - point;
      x.centre = point + 2 * d.dot(axis) * axis - d;  // half a turn about the line through `point`
    }
    return b;
  };
  auto min_distance = [&](const std::vector<StressAtom>& b) {
    double best = std::numeric_limits<double>::infinity();
    for (const StressAtom& x : a)
      for (const StressAtom& y : b) best = std::min(best, (x.centre - y.centre).norm());
    return best;
  };
  double lo = 0, hi = 0;
  for (const StressAtom& x : a) hi = std::max(hi, (x.centre - centre).norm());
  hi += 4;
  for (int i = 0; i < 40; ++i) {  // the copies' closest pair grows with the offset
    const double mid = 0.5 * (lo + hi);
    (min_distance(partner(mid)) < closest ? lo : hi) = mid;
  }
  std::vector<StressAtom> atoms = a;
  for (const StressAtom& x : partner(hi)) atoms.push_back(x);
  for (StressAtom& x : atoms) x.centre += 0.3 * Vec3(rng.normal(), rng.normal(), rng.normal());
  return atoms;
}

/// The class of the 4.2 Å crystal structure 3P3W whose sweep once ran away at
/// probe 0 (tests/data/regression/README.md): bundled proteins with their side
/// chains misplaced, and dimers packed tighter than contact, at probes 0,
/// 0.5 and 1.4, each swept in kLowResDirections directions.
void lowres_models(Suite& s) {
  const ModelAtoms crambin = bundled_model("crambin_1crn.pdb");
  const ModelAtoms gramicidin = bundled_model("gramicidinA_1grm_model1.pdb");
  for (const double p : {0.0, 0.5, 1.4}) {
    {
      StressCase c = s.begin("lowres", "crambin-side-chains");
      Rng rng(c.seed);
      c.probe = p;
      c.atoms = displaced_side_chains(crambin, rng);
      c.note = "crambin with each side chain moved 0.5-1.5 Å and 0.2 Å noise, clashes kept";
      c.name += "/p" + num(p);
      add_directions(s, c, kLowResDirections);
    }
    {
      StressCase c = s.begin("lowres", "gramicidin-packed-dimer");
      Rng rng(c.seed);
      c.probe = p;
      c.atoms = packed_dimer(displaced_side_chains(gramicidin, rng), 2.0, rng);
      c.note = "two gramicidin A chains (side chains moved) packed to a closest pair of 2 Å, 0.3 Å noise";
      c.name += "/p" + num(p);
      add_directions(s, c, kLowResDirections);
    }
  }
}

void add_twins(Suite& s) {
  const std::size_t n = s.cases.size();
  std::string family;
  int k = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (s.cases[i].family != family) family = s.cases[i].family, k = 0;
    if (k++ % 2 != 0) continue;
    Rng rng(case_seed(s.seed, s.cases[i].name + "/rt"));
    s.cases.push_back(rotated_translated(s.cases[i], rng));
  }
}

void check_unique(const std::vector<StressCase>& cases) {
  std::set<std::string> names;
  for (const StressCase& c : cases)
    if (!names.insert(c.name).second) throw std::logic_error("stress generator: duplicate case name " + c.name);
}

}  // namespace

std::vector<StressCase> generate_suite(std::uint64_t suite_seed) {
  Suite s{suite_seed, {}};
  clusters(s);
  proteins(s);
  lattices(s);
  shells(s);
  rings(s);
  helices(s);
  thresholds(s);
  duplicates(s);
  add_twins(s);
  // The fallback's families bring their own directions and transforms.
  membranes(s);
  cages(s);
  packings(s);
  channels(s);
  lowres_models(s);
  // Keep each family together: twins after their family's base cases.
  std::stable_sort(s.cases.begin(), s.cases.end(), [](const StressCase& a, const StressCase& b) {
    static const std::vector<std::string> order = {"cluster", "protein",   "lattice",   "shell",    "ring",
                                                   "helix",   "threshold", "duplicate", "membrane", "cage",
                                                   "packing", "channel",   "lowres"};
    auto rank = [](const std::string& f) { return std::find(order.begin(), order.end(), f) - order.begin(); };
    return rank(a.family) < rank(b.family);
  });
  check_unique(s.cases);
  return s.cases;
}

std::vector<StressCase> generate_extra(std::uint64_t suite_seed, std::size_t count) {
  Suite s{suite_seed, {}};
  for (std::size_t k = 0; k < count; ++k) {
    const std::string tag = "extra" + std::to_string(k);
    StressCase c;
    switch (k % 4) {
      case 0: {
        c = s.begin("cluster", tag);
        Rng rng(c.seed);
        c.probe = rng.probe();
        const int n = 5 + static_cast<int>(rng.index(116));
        const double fraction = std::pow(10.0, rng.uniform(-1.7, -0.4));
        const double side = std::cbrt(n * 4.0 / 3.0 * kPi * 1.6 * 1.6 * 1.6 / fraction);
        for (int i = 0; i < n; ++i)
          c.atoms.push_back(
              {Vec3(rng.uniform(0, side), rng.uniform(0, side), rng.uniform(0, side)), rng.uniform(1.2, 2.0)});
        c.note = "n " + std::to_string(n) + ", packing fraction " + num(fraction);
        break;
      }
      case 1: {
        c = s.begin("protein", tag);
        Rng rng(c.seed);
        c.probe = rng.probe();
        c.atoms = pseudo_protein(10 + static_cast<int>(rng.index(141)), rng);
        c.note = "self-avoiding N-CA-C chain, 1.5 Å bonds, side atoms";
        break;
      }
      case 2: {
        c = s.begin("ring", tag);
        Rng rng(c.seed);
        c.probe = rng.probe();
        const int n = 4 + static_cast<int>(rng.index(27));
        const double R = unshrunk(1.7, c.probe), f = rng.uniform(1.0, 2.3);
        c.atoms = ring(n, f * R / (2 * std::sin(kPi / n)), 1.7);
        c.note = "ring of " + std::to_string(n) + ", neighbours " + num(f) + " R apart";
        break;
      }
      default: {
        c = s.begin("threshold", tag);
        Rng rng(c.seed);
        c.probe = rng.probe();
        const double r1 = rng.uniform(1.5, 1.9), r2 = rng.uniform(1.5, 1.9);
        const double d = (rng.uniform() < 0.5 ? -1 : 1) * std::pow(10.0, rng.uniform(-7, -2));
        const double dist = unshrunk(r1, c.probe) + unshrunk(r2, c.probe) + d;
        c.atoms = {{Vec3::Zero(), r1}, {dist * rng.unit_vector(), r2}};
        c.note = "pair, gap " + num(d) + " Å";
        break;
      }
    }
    s.add(std::move(c));
  }
  const std::size_t n = s.cases.size();
  for (std::size_t i = 0; i < n; i += 2) {
    Rng rng(case_seed(suite_seed, s.cases[i].name + "/rt"));
    s.cases[i] = rotated_translated(s.cases[i], rng);
  }
  check_unique(s.cases);
  return s.cases;
}

}  // namespace skinmesh::stress

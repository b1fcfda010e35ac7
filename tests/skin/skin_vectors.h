// tests/skin/skin_vectors.h: reader for tests/data/skin_vectors.txt, the
// reference values (foci, skin samples with gradient, curvatures and rho,
// critical points of the height) of the small configurations of
// tests/skin/skin_test_util.h. The file's header says how the values were
// computed and gives the record format. papers/skin/skin_math.md §10.
#pragma once

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/errors.h"
#include "core/types.h"
#include "geometry/kernel/weighted_point.h"

namespace skinmesh::test {

/// The reference values of one configuration of tests/data/skin_vectors.txt.
struct SkinVectors {
  /// A simplex of the regular triangulation: its input vertices (sorted), focus
  /// z_X (Å) and focus weight w_X (Å²).
  struct Simplex {
    std::vector<Index> vertices;
    Vec3 focus = Vec3::Zero();
    double weight = 0;
  };
  /// A point x on the skin (Å), the simplex whose mixed cell holds it (input
  /// vertices, sorted), f(x) (Å²), grad f(x) (Å), the principal curvatures
  /// (1/Å; on hyperboloids k1 is the circle direction) and rho(x) (Å).
  struct Sample {
    std::string name;
    Vec3 x = Vec3::Zero();
    std::vector<Index> cell;
    double f = 0;
    Vec3 gradient = Vec3::Zero();
    double k1 = 0, k2 = 0, rho = 0;
  };
  /// A critical point (Å) of h(x) = e·x; index 0 minimum, 1 saddle, 2 maximum
  /// (the values of morse::CriticalKind).
  struct Critical {
    Vec3 e = Vec3::Zero();
    int index = 0;
    Vec3 position = Vec3::Zero();
  };
  /// Numbers of critical points of h(x) = e·x.
  struct Counts {
    Vec3 e = Vec3::Zero();
    int minima = 0, saddles = 0, maxima = 0;
  };

  std::string name;
  std::vector<geometry::WeightedPoint> points;
  std::vector<Simplex> simplices;
  std::vector<Sample> samples;
  std::vector<Critical> critical;
  std::vector<Counts> counts;
  int euler_skin = 0;  ///< chi(skin) = 2 chi(K0)

  /// The simplex with these input vertices. Throws std::out_of_range if absent.
  const Simplex& simplex(std::vector<Index> v) const {
    std::sort(v.begin(), v.end());
    for (const Simplex& s : simplices)
      if (s.vertices == v) return s;
    throw std::out_of_range("skin_vectors: no such simplex in configuration " + name);
  }
  /// Number of listed simplices of dimension d (d + 1 vertices).
  Index num_simplices(int d) const {
    Index n = 0;
    for (const Simplex& s : simplices)
      if (static_cast<int>(s.vertices.size()) == d + 1) ++n;
    return n;
  }
  /// The sample called `n`. Throws std::out_of_range if absent.
  const Sample& sample(const std::string& n) const {
    for (const Sample& s : samples)
      if (s.name == n) return s;
    throw std::out_of_range("skin_vectors: no sample '" + n + "' in configuration " + name);
  }
  /// The critical-point counts for direction e (within 1e-12). Throws
  /// std::out_of_range if absent.
  const Counts& counts_for(const Vec3& e) const {
    for (const Counts& c : counts)
      if ((c.e - e).norm() <= 1e-12) return c;
    throw std::out_of_range("skin_vectors: no critical-point counts for this direction in " + name);
  }
  /// The listed critical points for direction e (within 1e-12).
  std::vector<Critical> critical_for(const Vec3& e) const {
    std::vector<Critical> out;
    for (const Critical& c : critical)
      if ((c.e - e).norm() <= 1e-12) out.push_back(c);
    return out;
  }
};

/// Path of the test-vector file (SKINMESH_TEST_DATA is set by CMake).
inline std::string skin_vectors_path() { return std::string(SKINMESH_TEST_DATA) + "/skin_vectors.txt"; }

/// Reads configuration `name` from tests/data/skin_vectors.txt. Throws
/// InputError (file:line: problem) if the file cannot be read, a record is
/// malformed, or the configuration is missing.
inline SkinVectors load_skin_vectors(const std::string& name) {
  const std::string path = skin_vectors_path();
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot open the test-vector file");
  SkinVectors out;
  bool found = false, inside = false;
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (const auto hash = line.find('#'); hash != std::string::npos) line.erase(hash);
    std::istringstream is(line);
    std::string kind;
    if (!(is >> kind)) continue;  // blank or comment
    auto fail = [&](const std::string& problem) { throw InputError(path, lineno, problem); };
    auto vec = [&]() {
      Vec3 v;
      if (!(is >> v.x() >> v.y() >> v.z())) fail("expected three numbers in a '" + kind + "' record");
      return v;
    };
    auto num = [&]() {
      double v = 0;
      if (!(is >> v)) fail("expected a number in a '" + kind + "' record");
      return v;
    };
    auto vertex_list = [&]() {
      int n = 0;
      if (!(is >> n) || n < 1 || n > 4) fail("expected a vertex count 1..4 in a '" + kind + "' record");
      std::vector<Index> v(static_cast<std::size_t>(n));
      for (Index& i : v)
        if (!(is >> i)) fail("expected a vertex index in a '" + kind + "' record");
      std::sort(v.begin(), v.end());
      return v;
    };
    if (kind == "config") {
      std::string n;
      if (!(is >> n)) fail("expected a name after 'config'");
      if (found && inside) break;  // the requested configuration is complete
      inside = n == name;
      if (inside) found = true, out.name = n;
    } else if (!inside) {
      continue;
    } else if (kind == "point") {
      geometry::WeightedPoint p;
      p.z = vec();
      p.w = num();
      out.points.push_back(p);
    } else if (kind == "simplex") {
      SkinVectors::Simplex s;
      s.vertices = vertex_list();
      s.focus = vec();
      s.weight = num();
      out.simplices.push_back(s);
    } else if (kind == "sample") {
      SkinVectors::Sample s;
      if (!(is >> s.name)) fail("expected a name after 'sample'");
      s.x = vec();
      s.cell = vertex_list();
      s.f = num();
      s.gradient = vec();
      s.k1 = num();
      s.k2 = num();
      s.rho = num();
      out.samples.push_back(s);
    } else if (kind == "critical") {
      SkinVectors::Critical c;
      c.e = vec();
      std::string k;
      if (!(is >> k)) fail("expected min, saddle or max in a 'critical' record");
      if (k == "min")
        c.index = 0;
      else if (k == "saddle")
        c.index = 1;
      else if (k == "max")
        c.index = 2;
      else
        fail("unknown kind of critical point '" + k + "'");
      c.position = vec();
      out.critical.push_back(c);
    } else if (kind == "counts") {
      SkinVectors::Counts c;
      c.e = vec();
      if (!(is >> c.minima >> c.saddles >> c.maxima)) fail("expected three counts in a 'counts' record");
      out.counts.push_back(c);
    } else if (kind == "euler") {
      if (!(is >> out.euler_skin)) fail("expected an integer after 'euler'");
    } else {
      fail("unknown record '" + kind + "'");
    }
    if (std::string extra; is >> extra) fail("unexpected '" + extra + "' at the end of a '" + kind + "' record");
  }
  if (!found) throw InputError(path, 0, "no configuration '" + name + "'");
  return out;
}

/// True if two lists of weighted points are the same up to `tol` (Å, Å²):
/// checks that the test vectors belong to the configuration under test.
inline bool same_points(const std::vector<geometry::WeightedPoint>& a, const std::vector<geometry::WeightedPoint>& b,
                        double tol = 1e-12) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if ((a[i].z - b[i].z).norm() > tol || std::abs(a[i].w - b[i].w) > tol) return false;
  return true;
}

}  // namespace skinmesh::test

// bench/bench_common.h: helpers shared by the Google Benchmark files of
// skinmesh_bench (bundled molecules, weighted points, a triangulation check).
// papers/conventions.md §3 "Benchmarks"; definitions in bench/bench_main.cpp.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "geometry/kernel/weighted_point.h"
#include "geometry/triangulation/regular_triangulation.h"
#include "skin/molecule.h"

namespace skinmesh::bench {

/// Probe radius (Å) of every molecular benchmark: the default of Cheng & Shi
/// §2.1 (a water molecule), the same as MeshingOptions::probe_radius.
inline constexpr double kProbeRadius = 1.4;

/// Absolute path of a bundled molecule: SKINMESH_DATA + "/" + file.
std::string data_path(const std::string& file);

/// Reads the bundled molecule `file` (e.g. "crambin_1crn.pdb") with the
/// default read options. Throws InputError if it cannot be read.
skin::Molecule load_molecule(const std::string& file);

/// Weighted points of a molecule: centre = atom centre, weight =
/// skin::atom_weight(r, probe) = 2 (r + probe)² (Cheng & Shi §2.1).
std::vector<geometry::WeightedPoint> weighted_points(const skin::Molecule& molecule, double probe = kProbeRadius);

/// load_molecule() then weighted_points() with probe radius `probe` (Å).
std::vector<geometry::WeightedPoint> molecule_points(const std::string& file, double probe = kProbeRadius);

/// Structural check of a finished triangulation, O(#tetrahedra): every
/// tetrahedron positively oriented (orient3d), neighbours symmetric, exactly
/// 4 outer faces, and local regularity (the vertex opposite each interior face
/// is not in conflict, RegularTriangulation::conflict()). Returns an empty
/// string if it passes, else a description of the first problem. It runs
/// outside the timed loops, so that a fast broken triangulation cannot win.
std::string check_triangulation(const geometry::RegularTriangulation& rt);

/// Sets counter `name` to the rate `per_iteration * iterations / time`
/// (benchmark::Counter::kIsRate over the total count). Call after the loop.
void set_rate(benchmark::State& state, const std::string& name, double per_iteration);

}  // namespace skinmesh::bench

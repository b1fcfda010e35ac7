// decompose/region_files.h: the decomposition carried out over several
// processes — the cuts written by the process that chose them, each slab's
// sweep written by the process that swept it, all read back by the process
// that glues them (decompose::sweep_decomposed()). Every value keeps its
// bytes, so the glued mesh is the one a single process makes.
// Notes: papers/decompose/README.md ("One structure over several processes")
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "decompose/decomposed.h"

namespace skinmesh::decompose {

/// The cuts of a decomposition as one process chose them (choose_cuts()),
/// with the fingerprint of the run they belong to: the processes that sweep
/// and glue its slabs must compute the same skin and complex, which they
/// test by comparing fingerprints (mesher::decomposition_fingerprint()).
struct CutsFile {
  std::uint64_t fingerprint = 0;
  std::vector<Cut> cuts;
};

/// One slab's sweep as one process made it (sweep_slab()).
struct RegionFile {
  std::uint64_t fingerprint = 0;
  SlabKey slab{kNoCut, kNoCut};
  SlabOutcome outcome;
};

/// Writes `cuts` to `path` (binary, native byte order, for read_cuts() of
/// the same build). Throws std::runtime_error naming the path if it cannot
/// be written; nothing is left at `path` then.
void write_cuts(const std::string& path, const CutsFile& cuts);
/// The cuts write_cuts() wrote. Throws InputError naming `path` if it cannot
/// be read, is not a cuts file or is truncated.
CutsFile read_cuts(const std::string& path);

/// Writes one slab's outcome to `path` (its mesh with every property, its
/// loops, rims, stats, or its failure). Throws as write_cuts().
void write_region(const std::string& path, const RegionFile& region);
/// The slab write_region() wrote. Throws InputError as read_cuts().
RegionFile read_region(const std::string& path);

}  // namespace skinmesh::decompose

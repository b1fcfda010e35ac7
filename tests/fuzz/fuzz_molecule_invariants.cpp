// tests/fuzz/fuzz_molecule_invariants.cpp: libFuzzer target for the invariants of
// skin::read_molecule_from_string() — every input is read as PDB, mmCIF, PQR and
// XYZR in turn, and each successful read must pass fuzz::check_molecule()
// (finite coordinates within ±kMaxCoordinate, radii in (0, kMaxRadius], ...).
// Seeded with the corpora of all four formats (tests/fuzz/run.sh).
#include "tests/fuzz/fuzz_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using Format = skinmesh::skin::ReadOptions::Format;
  for (const Format f : {Format::Pdb, Format::Mmcif, Format::Pqr, Format::Xyzr, Format::Xyzrn})
    skinmesh::fuzz::molecule_input(data, size, f, /*check=*/true);
  return 0;
}

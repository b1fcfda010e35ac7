// tests/fuzz/fuzz_mesh_invariants.cpp: libFuzzer target for the invariants of
// geometry::read_mesh_from_bytes() — every input is read as PLY, OFF and OBJ in
// turn, and each successful read must pass fuzz::check_mesh() (finite positions
// and normals, one normal and atom id per vertex when present, triangle indices
// in range). Seeded with the corpora of all three formats (tests/fuzz/run.sh).
#include "tests/fuzz/fuzz_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using skinmesh::geometry::MeshFormat;
  for (const MeshFormat f : {MeshFormat::Ply, MeshFormat::Off, MeshFormat::Obj})
    skinmesh::fuzz::mesh_input(data, size, f, /*check=*/true);
  return 0;
}

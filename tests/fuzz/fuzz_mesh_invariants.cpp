// tests/fuzz/fuzz_mesh_invariants.cpp: libFuzzer target for the invariants of
// geometry::read_mesh_from_bytes() — every input is read as PLY, OFF, OBJ, STL,
// VTK and MSMS in turn, and each successful read must pass fuzz::check_mesh()
// (finite positions and normals, one normal, atom id and rho per vertex when
// present, triangle indices in range). Seeded with the corpora of all six
// formats (tests/fuzz/run.sh).
#include "tests/fuzz/fuzz_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using skinmesh::geometry::MeshFormat;
  for (const MeshFormat f :
       {MeshFormat::Ply, MeshFormat::Off, MeshFormat::Obj, MeshFormat::Stl, MeshFormat::Vtk, MeshFormat::Msms})
    skinmesh::fuzz::mesh_input(data, size, f, /*check=*/true);
  return 0;
}

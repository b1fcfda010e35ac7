// tests/fuzz/fuzz_mesh_invariants.cpp: libFuzzer target for the invariants of
// the mesh readers — every input is read as PLY, OFF, OBJ, STL,
// legacy VTK, XML VTK (.vtp and .vtu) and MSMS in turn, and each successful read must pass fuzz::check_mesh()
// (finite positions and normals, one normal, attribute value and atom id per
// vertex when present, triangle indices in range). Seeded with the corpora of all
// seven formats (tests/fuzz/run.sh).
#include "tests/fuzz/fuzz_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using skinmesh::fuzz::MeshInput;
  for (const MeshInput f : {MeshInput::Ply, MeshInput::Off, MeshInput::Obj, MeshInput::Stl, MeshInput::Vtk,
                            MeshInput::Vtp, MeshInput::Vtu, MeshInput::Msms})
    skinmesh::fuzz::mesh_input(data, size, f, /*check=*/true);
  return 0;
}

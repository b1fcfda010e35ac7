// tests/fuzz/fuzz_vtkxml.cpp: libFuzzer target — every input is read as an XML VTK
// PolyData (.vtp) and UnstructuredGrid (.vtu) file by skinmesh::fuzz::mesh_input()
// (tests/fuzz/fuzz_readers.h says what counts as a bug).
#include "tests/fuzz/fuzz_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  skinmesh::fuzz::mesh_input(data, size, skinmesh::fuzz::MeshInput::Vtp, /*check=*/false);
  skinmesh::fuzz::mesh_input(data, size, skinmesh::fuzz::MeshInput::Vtu, /*check=*/false);
  return 0;
}

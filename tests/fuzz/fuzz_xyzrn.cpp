// tests/fuzz/fuzz_xyzrn.cpp: libFuzzer target — every input is read as a XYZRN file (x y z r [n [name]]) by
// skin::read_molecule_from_string() (tests/fuzz/fuzz_readers.h says what counts as a bug).
#include "tests/fuzz/fuzz_readers.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  skinmesh::fuzz::molecule_input(data, size, skinmesh::skin::ReadOptions::Format::Xyzrn, /*check=*/false);
  return 0;
}

// tests/fuzz/fuzz_readers.h: what the libFuzzer targets of tests/fuzz/ share —
// one input through skin::read_molecule_from_string(),
// geometry::read_mesh_from_bytes() or skin::read_msms_from_bytes(), in memory
// (no temporary files).
//
// The readers document one exception for bad input, skinmesh::InputError
// (core/errors.h); it is caught and the input rejected. Anything else — a
// crash, a sanitizer report, another exception (libFuzzer reports it as a deadly
// signal through std::terminate), a hang or an allocation beyond the limits of
// the run (-timeout, -rss_limit_mb, -malloc_limit_mb; see tests/fuzz/run.sh) —
// is a bug. With `check` set, a successful read must also satisfy the invariants
// of check_molecule() / check_mesh(); a violation aborts with a message.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <vector>
#include "core/errors.h"
#include "geometry/io/mesh_io.h"
#include "geometry/kernel/weighted_point.h"
#include "skin/molecule_io.h"
#include "skin/skin_mesh_io.h"

namespace skinmesh::fuzz {

/// Aborts (a crash for libFuzzer, which saves the input) with `what`.
[[noreturn]] inline void invariant_failed(const char* what, std::size_t index) {
  std::fprintf(stderr, "fuzz invariant violated: %s (item %zu)\n", what, index);
  std::abort();
}

/// The invariants of a Molecule returned by read_molecule() (molecule_io.h): at
/// least one atom; every coordinate finite and within ±geometry::kMaxCoordinate;
/// every radius finite, > 0 and <= skin::kMaxRadius; an element for every PDB
/// and mmCIF atom (an unknown element is an InputError); lines >= 0, and > 0
/// for PDB (gemmi returns only atoms of records the pre-scan checked and
/// indexed, skin/molecule_io_gemmi.cpp); non-empty notes.
inline void check_molecule(const skin::Molecule& m, skin::ReadOptions::Format format) {
  if (m.atoms.empty()) invariant_failed("molecule without atoms", 0);
  for (std::size_t i = 0; i < m.atoms.size(); ++i) {
    const skin::Atom& a = m.atoms[i];
    for (int k = 0; k < 3; ++k)
      if (!std::isfinite(a.centre[k]) || std::abs(a.centre[k]) > geometry::kMaxCoordinate)
        invariant_failed("atom coordinate not finite or outside ±kMaxCoordinate", i);
    if (!std::isfinite(a.radius) || a.radius <= 0.0 || a.radius > skin::kMaxRadius)
      invariant_failed("atom radius not in (0, kMaxRadius]", i);
    if ((format == skin::ReadOptions::Format::Pdb || format == skin::ReadOptions::Format::Mmcif) && a.element.empty())
      invariant_failed("PDB/mmCIF atom without element", i);
    if (a.line < 0) invariant_failed("negative atom line", i);
    if (format == skin::ReadOptions::Format::Pdb && a.line == 0)
      invariant_failed("PDB atom without its source line (a record the pre-scan did not check?)", i);
  }
  for (std::size_t i = 0; i < m.notes.size(); ++i)
    if (m.notes[i].empty()) invariant_failed("empty note", i);
}

/// The invariants of an IndexedMesh returned by read_mesh() (mesh_io.h) or
/// read_msms_from_bytes() (skin_mesh_io.h): every position finite; normals
/// empty or one per vertex and finite; every attribute one value per vertex,
/// an integer one's values integers in the int32 range; atom ids empty or one
/// per vertex; every triangle index < the number of vertices. (The readers do
/// not bound coordinates by geometry::kMaxCoordinate: a mesh file may hold any
/// finite position.)
inline void check_mesh(const geometry::IndexedMesh& m, const std::vector<geometry::VertexAttribute>& attributes,
                       const skin::SkinVertexData& data) {
  const std::size_t n = m.positions.size();
  for (std::size_t i = 0; i < n; ++i)
    if (!m.positions[i].allFinite()) invariant_failed("vertex position not finite", i);
  if (!m.normals.empty() && m.normals.size() != n) invariant_failed("normals not one per vertex", m.normals.size());
  for (std::size_t i = 0; i < m.normals.size(); ++i)
    if (!m.normals[i].allFinite()) invariant_failed("vertex normal not finite", i);
  for (std::size_t k = 0; k < attributes.size(); ++k) {
    const geometry::VertexAttribute& a = attributes[k];
    if (a.values.size() != n) invariant_failed("attribute not one value per vertex", k);
    if (a.integer)
      for (double v : a.values)
        if (v != std::floor(v) || v < -2147483648.0 || v > 2147483647.0)
          invariant_failed("integer attribute value not an int32", k);
  }
  if (!data.atom.empty() && data.atom.size() != n) invariant_failed("atom ids not one per vertex", data.atom.size());
  for (std::size_t i = 0; i < m.triangles.size(); ++i)
    for (const Index v : m.triangles[i])
      if (v >= n) invariant_failed("triangle index out of range", i);
}

/// The name a format's input goes by in messages (its extension matters only
/// for ReadOptions::Format::Auto, which the targets do not use).
inline const char* molecule_name(skin::ReadOptions::Format format) {
  switch (format) {
    case skin::ReadOptions::Format::Pdb:
      return "fuzz.pdb";
    case skin::ReadOptions::Format::Mmcif:
      return "fuzz.cif";
    case skin::ReadOptions::Format::Pqr:
      return "fuzz.pqr";
    case skin::ReadOptions::Format::Xyzr:
      return "fuzz.xyzr";
    case skin::ReadOptions::Format::Xyzrn:
      return "fuzz.xyzrn";
    case skin::ReadOptions::Format::Auto:
      break;
  }
  return "fuzz";
}

/// Reads `data` as a molecule file of `format`. The options vary with the input
/// length (bit 0: keep_water, bit 1: drop hydrogens, bits 2-3: the first model,
/// model 1, model 2, or the first model's assembly "1") so that every path of
/// the readers is reached without a byte of the input spent on them.
inline void molecule_input(const std::uint8_t* data, std::size_t size, skin::ReadOptions::Format format, bool check) {
  skin::ReadOptions opt;
  opt.format = format;
  opt.keep_water = (size & 1u) != 0;
  opt.keep_hydrogens = (size & 2u) == 0;
  const std::size_t model_bits = (size >> 2) & 3u;
  if (model_bits == 3)
    opt.assembly = "1";
  else
    opt.model = static_cast<int>(model_bits);
  try {
    const skin::Molecule m = skin::read_molecule_from_string(std::string(reinterpret_cast<const char*>(data), size),
                                                             molecule_name(format), opt);
    if (check) check_molecule(m, format);
  } catch (const InputError&) {
    // Bad input, reported as documented.
  }
}

/// The mesh file formats the targets read: the geometric ones and MSMS.
enum class MeshInput { Ply, Off, Obj, Stl, Vtk, Vtp, Vtu, Msms };

/// Reads `data` as a mesh file of `format`.
inline void mesh_input(const std::uint8_t* data, std::size_t size, MeshInput format, bool check) {
  try {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    std::vector<geometry::VertexAttribute> attributes;
    skin::SkinVertexData vertex_data;
    geometry::IndexedMesh m;
    if (format == MeshInput::Msms) {
      m = skin::read_msms_from_bytes(bytes, "fuzz", &vertex_data);
    } else {
      const geometry::MeshFormat geometric[] = {
          geometry::MeshFormat::Ply, geometry::MeshFormat::Off, geometry::MeshFormat::Obj, geometry::MeshFormat::Stl,
          geometry::MeshFormat::Vtk, geometry::MeshFormat::Vtp, geometry::MeshFormat::Vtu};
      m = geometry::read_mesh_from_bytes(bytes, geometric[static_cast<int>(format)], "fuzz", &attributes);
    }
    if (check) check_mesh(m, attributes, vertex_data);
  } catch (const InputError&) {
    // Bad input, reported as documented.
  }
}

}  // namespace skinmesh::fuzz

// skin/molecule.h: a molecule as the mesher sees it, a list of atoms (balls with
// centre and radius, Å) plus the identifiers needed to report on them.
// Read by skin/molecule_io; turned into weighted points b = (z, r²) downstream.
#pragma once

#include <string>
#include <vector>

#include "core/types.h"

namespace skinmesh::skin {

// Atom Definition

/// One atom: a ball of radius `radius` (Å, > 0) about `centre` (Å), plus where it
/// came from. `element` is the symbol in standard capitalisation ("C", "Cl", "Fe"),
/// or empty when the format has none (XYZR). `name`, `residue` and `chain` are the
/// trimmed atom name, residue name and chain id (empty when absent);
/// `residue_number` and `serial` are as read (0 when absent). `line` is the 1-based
/// line of the source file that holds the atom's record, or 0 if unknown.
struct Atom {
  Vec3 centre = Vec3::Zero();
  double radius = 0.0;
  std::string element;
  std::string name;
  std::string residue;
  std::string chain;
  int residue_number = 0;
  /// The residue's insertion code (PDB column 27, mmCIF pdbx_PDB_ins_code);
  /// ' ' for none and for formats without one.
  char insertion_code = ' ';
  int serial = 0;
  int line = 0;
  /// The name field of an .xyzrn record as the file has it (MSMS copies it
  /// to the vertices of its .vert file; MaSIF writes chain_resnum_icode_
  /// resname_atomname_colour there); empty for other formats.
  std::string msms_name;
};

// Molecule Definition

/// The atoms read from one file, in file order (first model, first alternate
/// location). `source` is the path they were read from. `notes` holds one
/// human-readable line for every atom that was skipped or repaired while reading
/// (a water, an alternate location, a zero-radius hydrogen, an element without a
/// Bondi radius, ...), formatted "file:line: what happened"; the library never
/// prints them, the caller decides.
struct Molecule {
  std::string source;
  std::vector<Atom> atoms;
  std::vector<std::string> notes;
};

}  // namespace skinmesh::skin

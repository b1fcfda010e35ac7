// skin/molecule_io_internal.h: the private header of read_molecule() — what the
// readers share and one reader per format, each in its own file:
//   molecule_io.cpp        format detection and dispatch (molecule_io.h), and the
//                          shared parts below: file reading, numbers, water and
//                          atom names, notes, the finished Molecule
//   molecule_io_gemmi.cpp  PDB and mmCIF through gemmi (the only file that
//                          includes gemmi: its types never leave it)
//   molecule_io_pqr.cpp    PQR
//   molecule_io_xyzr.cpp   XYZR and XYZRN (MSMS)
// Only skin/molecule_io*.cpp include this header.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "skin/molecule.h"
#include "skin/molecule_io.h"

namespace skinmesh::skin::molecule_io_detail {

// Shared Parts (molecule_io.cpp)

/// Reads the whole file (gunzipped if the name ends in .gz, case-insensitive).
/// Throws InputError(path, 0, "cannot open file (...)" or "cannot read file (...)").
std::string read_text(const std::string& path);

/// All of `field` (surrounding blanks ignored, a leading '+' allowed) as a finite
/// double. Throws InputError(path, line, "non-numeric <what> '<field>'") if
/// anything is left over or nothing is a number, or "non-finite <what> '<field>'"
/// for nan, inf or overflow (`field` trimmed in the message).
double parse_number(const std::string& path, int line, std::string_view field, const char* what);

/// The leading (optionally signed) integer of `s`, or 0 if there is none. Used for
/// identifiers that only label atoms (serials, residue numbers).
int leading_int(std::string_view s);

/// Residue names of water: gemmi's Residue::is_water() (HOH, DOD, WAT, H2O) plus the
/// names molecular-dynamics packages use.
bool is_water_residue(std::string_view residue);

/// "atom CA of SER A 45" (chain and residue left out when empty).
std::string describe(std::string_view name, std::string_view residue, std::string_view chain, int residue_number);

/// Collects notes with their line so they can be listed in file order.
class NoteList {
 public:
  explicit NoteList(std::string path) : path_(std::move(path)) {}
  /// Adds the note "path:line: text" ("path: text" when `line` is 0, unknown).
  void add(int line, const std::string& text);
  /// The number of notes added.
  std::size_t size() const { return notes_.size(); }
  /// The notes in order of their line (stable: notes of one line keep their
  /// order; line 0 first), moved out of the list.
  std::vector<std::string> sorted();
  /// The first note added. Pre: size() > 0.
  const std::string& first() const { return notes_.front().second; }

 private:
  std::string path_;
  std::vector<std::pair<int, std::string>> notes_;
};

/// The Molecule of `path` with atoms and notes in file order (atoms sorted by
/// line when every line is known), or InputError(path, 0, "no atoms found")
/// naming the number of skipped atoms and the first note, or InputError(path,
/// atom line, ...) for a non-finite coordinate, a coordinate outside
/// ±geometry::kMaxCoordinate or a radius above kMaxRadius.
Molecule finish(const std::string& path, std::vector<Atom> atoms, NoteList& notes);

// Readers: each reads `text`, the content of the file `path` (the name used in
// notes and errors), as read_molecule() documents for its format and throws
// InputError(path, line, problem).

/// PDB through gemmi, after the column pre-scan (molecule_io_gemmi.cpp).
Molecule read_pdb(const std::string& path, const std::string& text, const ReadOptions& opt);

/// mmCIF through gemmi, after the _atom_site pre-scan (molecule_io_gemmi.cpp).
Molecule read_mmcif(const std::string& path, const std::string& text, const ReadOptions& opt);

/// The model numbers of a PDB text (its MODEL records' serials, in order; {1}
/// without any) and of an mmCIF text (its distinct pdbx_PDB_model_num values,
/// in order; {1} without that item) (molecule_io_gemmi.cpp). Throw InputError
/// for an mmCIF text gemmi cannot parse.
std::vector<int> pdb_model_numbers(std::string_view text);
std::vector<int> mmcif_model_numbers(const std::string& path, const std::string& text);

/// PQR: radii from the file (molecule_io_pqr.cpp).
Molecule read_pqr(const std::string& path, const std::string& text, const ReadOptions& opt);

/// XYZR (MSMS): `x y z r` per line; with `names` (.xyzrn) `x y z r [n [name]]`,
/// the name kept as Atom::msms_name and, if it reads as MaSIF's
/// chain_resnum_icode_resname_atomname[_colour], split into the atom's fields
/// (molecule_io_xyzr.cpp).
Molecule read_xyzr(const std::string& path, const std::string& text, bool names);

}  // namespace skinmesh::skin::molecule_io_detail

// skin/molecule_io.h: read_molecule() turns a PDB, mmCIF, PQR or XYZR file into a
// Molecule (atom centres and radii, Å). The first stage of the pipeline (papers/conventions.md §2).
// PDB and mmCIF go through gemmi; radii come from Bondi (skin/element_radii.h).
// Implemented in skin/molecule_io.cpp (dispatch and shared parts) and one file per
// reader, skin/molecule_io_{gemmi,pqr,xyzr}.cpp (see skin/molecule_io_internal.h).
#pragma once

#include <string>
#include <vector>

#include "skin/molecule.h"

namespace skinmesh::skin {

/// The largest atom radius read_molecule() accepts (Å): far above any atom or
/// coarse-grained bead, and with any probe radius well inside the weight range
/// of geometry::kMaxWeight.
inline constexpr double kMaxRadius = 1e4;

// Molecule Reading Options

/// What read_molecule() keeps and how it recognises the format.
struct ReadOptions {
  /// Keep water molecules (residues HOH, WAT, DOD, H2O, TIP3, SOL, ...). Default:
  /// drop them, one note each.
  bool keep_water = false;
  /// Keep hydrogen (and deuterium) atoms when the file has them. Default: keep.
  bool keep_hydrogens = true;
  /// File formats. Auto chooses by extension: .pdb .ent -> Pdb; .cif .mmcif ->
  /// Mmcif; .pqr -> Pqr; .xyzr -> Xyzr; .xyzrn -> Xyzrn; each optionally
  /// followed by .gz (gzip).
  enum class Format { Auto, Pdb, Mmcif, Pqr, Xyzr, Xyzrn };
  Format format = Format::Auto;
  /// Which model of a PDB or mmCIF file: 0, the first (default); N >= 1, the
  /// model numbered N (PDB "MODEL N", mmCIF pdbx_PDB_model_num N; a file
  /// without models holds model 1 only). model_numbers() lists them.
  int model = 0;
  /// If not empty, the biological assembly of this id (PDB REMARK 350
  /// "BIOMOLECULE: id", mmCIF _pdbx_struct_assembly.id), read with gemmi and
  /// expanded: the model's atoms copied by every operator of the assembly onto
  /// the chains (PDB) or label_asym_id subchains (mmCIF) it names. PDB and mmCIF only.
  std::string assembly;
  /// If not empty, only the atoms of these chains (Atom::chain, after the
  /// assembly's expansion, so "A2" names a copy), in file order; a chain that
  /// holds no atom is an error. chain_names() lists a file's chains.
  std::vector<std::string> chains;
};

// Molecule Reading Public Functions

/// Reads the atoms of `path`, in file order.
///
/// - PDB (fixed columns; x, y, z from columns 31-54) and mmCIF (_atom_site) are
///   read with gemmi: the model ReadOptions::model (the first by
///   default), expanded to ReadOptions::assembly if one is named; first alternate location only (an atom is
///   kept if its altloc is blank or the first letter seen for that atom; a residue
///   whose atoms all carry one other letter, a micro-heterogeneity alternative, is
///   dropped whole); waters dropped unless `opt.keep_water`; hydrogens dropped if
///   `!opt.keep_hydrogens`. The element comes from the element column (PDB columns
///   77-78, mmCIF type_symbol), else is guessed by gemmi from the atom name (one
///   summary note). The radius is Bondi's (bondi_radius); an element Bondi does
///   not list gets kFallbackRadius and a note. PDB: only the ATOM, HETATM, MODEL,
///   ENDMDL, TER and END records are read, nothing after the first model, a line
///   up to column 120 (gemmi's limit), NUL and CR bytes as blanks; mmCIF: only
///   the _atom_site items, an integer there (serial, residue number) beyond
///   ±INT_MAX as absent (0).
/// - PQR: whitespace separated `ATOM|HETATM serial name resName [chain] resSeq x y
///   z charge radius`; x, y, z, charge, radius are the last five fields. The
///   radius is the file's. A hydrogen with radius 0 is skipped with a note. The
///   element is guessed from the atom name (first letter after leading digits, or
///   the name itself for single-atom ion residues such as "NA NA").
/// - XYZR (MSMS): `x y z r` per line, extra fields ignored, blank lines and `#`
///   comments allowed; element, names and ids empty/0, serial = 1-based index.
///
/// Every skipped or repaired atom gets one line in Molecule::notes
/// ("path:line: ..."). Throws InputError(path, line, problem) for: a file that
/// cannot be opened or read ("cannot open file"), an unknown format, a malformed
/// record, a non-numeric or non-finite coordinate ("non-numeric x coordinate
/// 'abc'", "non-finite y coordinate 'nan'"), a coordinate outside
/// ±geometry::kMaxCoordinate, a radius <= 0 (except the hydrogen case above) or
/// above kMaxRadius, an unknown element, and a file without atoms ("no atoms
/// found").
/// Line numbers are 1-based; 0 when unknown (some errors reported by gemmi
/// itself, an mmCIF _atom_site written as tag-value pairs rather than a loop).
Molecule read_molecule(const std::string& path, const ReadOptions& opt = {});

/// Reads the atoms of `text`, the whole content of a molecule file (not gzipped),
/// exactly as read_molecule() reads a file: `name` stands for the path in
/// Molecule::source, the notes and every InputError(name, line, problem), and
/// chooses the format by its extension when opt.format is Auto. The in-memory
/// entry point of read_molecule(), which reads the file and calls it.
Molecule read_molecule_from_string(const std::string& text, const std::string& name, const ReadOptions& opt = {});

/// The model numbers of `path`, in file order (ReadOptions::model): PDB MODEL
/// records, mmCIF pdbx_PDB_model_num values; {1} for a file without models
/// and for PQR, XYZR and XYZRN. Throws InputError as read_molecule() does for
/// an unreadable file or unknown format.
std::vector<int> model_numbers(const std::string& path, const ReadOptions& opt = {});

/// The chains of `molecule`, in the order of their first atoms (a blank
/// chain as ""): what ReadOptions::chains selects from.
std::vector<std::string> chain_names(const Molecule& molecule);

/// The format read_molecule() would choose for `path` by its extension (case
/// insensitive, a trailing .gz ignored): Pdb, Mmcif, Pqr, Xyzr or Xyzrn. Throws InputError(path, 0, "unknown
/// format (expected .pdb, .cif, .pqr, .xyzr or .xyzrn)") for anything else.
ReadOptions::Format format_from_extension(const std::string& path);

}  // namespace skinmesh::skin

// skin/molecule_io.cpp: the public functions of molecule_io.h — the format by
// extension and read_molecule() dispatching to one reader per format
// (molecule_io_gemmi.cpp for PDB and mmCIF, molecule_io_pqr.cpp,
// molecule_io_xyzr.cpp) — and what the readers share (molecule_io_internal.h):
// reading a possibly gzipped file, number parsing, water residues and atom
// descriptions, the notes, and the finished Molecule.
#include "skin/molecule_io.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>
#include <vector>

#include <zlib.h>

#include "core/errors.h"
#include "core/read_file.h"
#include "core/text_split.h"
#include "geometry/kernel/weighted_point.h"
#include "skin/molecule_io_internal.h"

namespace skinmesh::skin {

namespace molecule_io_detail {

using skinmesh::trim;

namespace {

/// "path:line" (or "path" when the line is unknown), the prefix of every note.
std::string where(const std::string& path, int line) { return line > 0 ? path + ":" + std::to_string(line) : path; }

// Number Parsing

/// The outcome of parse_double().
enum class NumberStatus { Ok, NonNumeric, NonFinite };

/// Parses all of `field` (surrounding blanks ignored, a leading '+' allowed) as a
/// double: Ok and `out` set, NonNumeric if anything is left over or nothing is a
/// number, NonFinite for nan, inf or overflow.
NumberStatus parse_double(std::string_view field, double& out) {
  field = trim(field);
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  if (field.empty()) return NumberStatus::NonNumeric;
  double v = 0.0;
  const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
  if (ptr != field.data() + field.size()) return NumberStatus::NonNumeric;
  if (ec == std::errc::result_out_of_range) {
    // from_chars reports underflow too; only overflow is non-finite.
    const std::string s(field);
    errno = 0;
    const double w = std::strtod(s.c_str(), nullptr);
    if (std::isinf(w)) return NumberStatus::NonFinite;
    out = w;
    return NumberStatus::Ok;
  }
  if (ec != std::errc()) return NumberStatus::NonNumeric;
  if (!std::isfinite(v)) return NumberStatus::NonFinite;
  out = v;
  return NumberStatus::Ok;
}

}  // namespace

// Text Helpers

std::string read_text(const std::string& path) {
  std::string text;
  if (lowercase(path).ends_with(".gz")) {
    gzFile f = gzopen(path.c_str(), "rb");
    if (!f) throw InputError(path, 0, std::string("cannot open file (") + std::strerror(errno) + ")");
    std::array<char, 1 << 16> buf;
    int n = 0;
    while ((n = gzread(f, buf.data(), static_cast<unsigned>(buf.size()))) > 0)
      text.append(buf.data(), static_cast<std::size_t>(n));
    int err = Z_OK;
    const std::string msg = n < 0 ? gzerror(f, &err) : "";
    gzclose(f);
    if (n < 0) throw InputError(path, 0, "cannot read file (gzip: " + msg + ")");
    return text;
  }
  return read_file(path);
}

// Number Parsing

double parse_number(const std::string& path, int line, std::string_view field, const char* what) {
  double v = 0.0;
  switch (parse_double(field, v)) {
    case NumberStatus::Ok:
      return v;
    case NumberStatus::NonNumeric:
      throw InputError(path, line, std::string("non-numeric ") + what + " '" + std::string(trim(field)) + "'");
    case NumberStatus::NonFinite:
      break;
  }
  throw InputError(path, line, std::string("non-finite ") + what + " '" + std::string(trim(field)) + "'");
}

int leading_int(std::string_view s) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  int v = 0;
  std::from_chars(s.data(), s.data() + s.size(), v);
  return v;
}

// Atom Classification

bool is_water_residue(std::string_view residue) {
  static const std::set<std::string, std::less<>> kWater = {"HOH",  "DOD",  "WAT",  "H2O", "HHO", "OHH", "SOL", "TIP",
                                                            "TIP3", "TIP4", "TIP5", "T3P", "T4P", "T5P", "SPC", "SPCE"};
  return kWater.count(uppercase(trim(residue))) != 0;
}

std::string describe(std::string_view name, std::string_view residue, std::string_view chain, int residue_number) {
  std::string s = "atom " + std::string(name);
  if (!residue.empty() || !chain.empty()) {
    s += " of";
    // Appended piece by piece: `s += " " + std::string(...)` trips a false
    // -Wrestrict of GCC 12 once this function is no longer inlined.
    if (!residue.empty()) {
      s += ' ';
      s += residue;
    }
    if (!chain.empty()) {
      s += ' ';
      s += chain;
    }
    s += ' ';
    s += std::to_string(residue_number);
  }
  return s;
}

// Notes and the Finished Molecule

void NoteList::add(int line, const std::string& text) { notes_.emplace_back(line, where(path_, line) + ": " + text); }

std::vector<std::string> NoteList::sorted() {
  std::stable_sort(notes_.begin(), notes_.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::string> out;
  out.reserve(notes_.size());
  for (auto& n : notes_) out.push_back(std::move(n.second));
  return out;
}

Molecule finish(const std::string& path, std::vector<Atom> atoms, NoteList& notes) {
  if (atoms.empty()) {
    std::string problem = "no atoms found";
    if (notes.size() > 0) problem += " (" + std::to_string(notes.size()) + " skipped, first: " + notes.first() + ")";
    throw InputError(path, 0, problem);
  }
  // The admissible range of the predicates (geometry/kernel/weighted_point.h): an
  // atom outside it is refused here, where its line is known.
  for (const Atom& a : atoms) {
    const char* axis[3] = {"x", "y", "z"};
    for (int k = 0; k < 3; ++k) {
      if (!std::isfinite(a.centre[k])) {  // the readers check their numbers: a safety net
        std::ostringstream os;
        os << "non-finite " << axis[k] << " coordinate '" << a.centre[k] << "'";
        throw InputError(path, a.line, os.str());
      }
      if (std::abs(a.centre[k]) > geometry::kMaxCoordinate) {
        std::ostringstream os;
        os << axis[k] << " coordinate " << a.centre[k] << " is outside the supported range ±"
           << geometry::kMaxCoordinate << " Å";
        throw InputError(path, a.line, os.str());
      }
    }
    if (a.radius > kMaxRadius) {
      std::ostringstream os;
      os << "radius " << a.radius << " is above the supported maximum " << kMaxRadius << " Å";
      throw InputError(path, a.line, os.str());
    }
  }
  const bool all_lines_known = std::all_of(atoms.begin(), atoms.end(), [](const Atom& a) { return a.line > 0; });
  if (all_lines_known)
    std::stable_sort(atoms.begin(), atoms.end(), [](const Atom& a, const Atom& b) { return a.line < b.line; });
  Molecule m;
  m.source = path;
  m.atoms = std::move(atoms);
  m.notes = notes.sorted();
  return m;
}

}  // namespace molecule_io_detail

namespace {

using molecule_io_detail::read_mmcif;
using molecule_io_detail::read_pdb;
using molecule_io_detail::read_pqr;
using molecule_io_detail::read_xyzr;

}  // namespace

// Molecule Reading Function Definitions

ReadOptions::Format format_from_extension(const std::string& path) {
  std::string name = lowercase(path);
  const std::size_t slash = name.find_last_of("/\\");
  if (slash != std::string::npos) name = name.substr(slash + 1);
  if (name.ends_with(".gz")) name.resize(name.size() - 3);
  if (name.ends_with(".pdb") || name.ends_with(".ent")) return ReadOptions::Format::Pdb;
  if (name.ends_with(".cif") || name.ends_with(".mmcif")) return ReadOptions::Format::Mmcif;
  if (name.ends_with(".pqr")) return ReadOptions::Format::Pqr;
  if (name.ends_with(".xyzr")) return ReadOptions::Format::Xyzr;
  if (name.ends_with(".xyzrn")) return ReadOptions::Format::Xyzrn;
  throw InputError(path, 0, "unknown format (expected .pdb, .cif, .pqr, .xyzr or .xyzrn)");
}

Molecule read_molecule(const std::string& path, const ReadOptions& opt) {
  ReadOptions resolved = opt;
  if (resolved.format == ReadOptions::Format::Auto) resolved.format = format_from_extension(path);
  return read_molecule_from_string(molecule_io_detail::read_text(path), path, resolved);
}

std::vector<int> model_numbers(const std::string& path, const ReadOptions& opt) {
  const ReadOptions::Format format = opt.format == ReadOptions::Format::Auto ? format_from_extension(path) : opt.format;
  if (format == ReadOptions::Format::Pdb)
    return molecule_io_detail::pdb_model_numbers(molecule_io_detail::read_text(path));
  if (format == ReadOptions::Format::Mmcif)
    return molecule_io_detail::mmcif_model_numbers(path, molecule_io_detail::read_text(path));
  return {1};
}

std::vector<std::string> chain_names(const Molecule& molecule) {
  std::vector<std::string> names;
  for (const Atom& a : molecule.atoms)
    if (std::find(names.begin(), names.end(), a.chain) == names.end()) names.push_back(a.chain);
  return names;
}

namespace {

/// The atoms of `m` in the chains `chains` (file order). Throws InputError for
/// a chain that holds no atom, listing the molecule's chains.
Molecule select_chains(Molecule m, const std::vector<std::string>& chains) {
  for (const std::string& c : chains)
    if (std::none_of(m.atoms.begin(), m.atoms.end(), [&](const Atom& a) { return a.chain == c; })) {
      std::string list;
      for (const std::string& n : chain_names(m)) list += (list.empty() ? "" : ", ") + (n.empty() ? "(blank)" : n);
      throw InputError(m.source, 0, "no atoms in chain '" + c + "' (the chains read: " + list + "; see --chains)");
    }
  std::erase_if(m.atoms,
                [&](const Atom& a) { return std::find(chains.begin(), chains.end(), a.chain) == chains.end(); });
  return m;
}

/// The reader of `format`.
Molecule read_format(const std::string& text, const std::string& name, ReadOptions::Format format,
                     const ReadOptions& opt);

}  // namespace

Molecule read_molecule_from_string(const std::string& text, const std::string& name, const ReadOptions& opt) {
  const ReadOptions::Format format = opt.format == ReadOptions::Format::Auto ? format_from_extension(name) : opt.format;
  Molecule m = read_format(text, name, format, opt);
  return opt.chains.empty() ? m : select_chains(std::move(m), opt.chains);
}

namespace {

Molecule read_format(const std::string& text, const std::string& name, ReadOptions::Format format,
                     const ReadOptions& opt) {
  if (format != ReadOptions::Format::Pdb && format != ReadOptions::Format::Mmcif &&
      (opt.model > 1 || !opt.assembly.empty()))
    throw InputError(name, 0, "models and assemblies are read from PDB and mmCIF files only (this file holds model 1)");
  switch (format) {
    case ReadOptions::Format::Pdb:
      return read_pdb(name, text, opt);
    case ReadOptions::Format::Mmcif:
      return read_mmcif(name, text, opt);
    case ReadOptions::Format::Pqr:
      return read_pqr(name, text, opt);
    case ReadOptions::Format::Xyzr:
      return read_xyzr(name, text, false);
    case ReadOptions::Format::Xyzrn:
      return read_xyzr(name, text, true);
    case ReadOptions::Format::Auto:
      break;
  }
  throw InputError(name, 0, "unknown format (expected .pdb, .cif, .pqr, .xyzr or .xyzrn)");
}

}  // namespace

}  // namespace skinmesh::skin

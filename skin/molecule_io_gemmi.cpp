// skin/molecule_io_gemmi.cpp: the PDB and mmCIF readers of read_molecule(),
// through gemmi. gemmi is used only in this file (papers/conventions.md §2): its types never
// leave it. Declared in molecule_io_internal.h.
//
// gemmi 0.5.7 reads the PDB coordinate columns 31-54 without checking them:
// pdb_impl::read_double() keeps whatever fast_float parses from the front of the
// field ("abc" -> 0, "12.1x4" -> 12.1, blank -> 0, "nan" -> NaN, "1e999" -> inf).
// So the PDB text is scanned here first: every ATOM/HETATM record of the first
// model must hold three complete, finite numbers in columns 31-38, 39-46, 47-54,
// else InputError with the line number. The same scan records each record's line,
// so atoms coming back from gemmi (regrouped by chain and residue) find their
// source line again by (x, y, z, name, altloc). gemmi reads a text the scan
// writes (scan_pdb()): the lines the scan checked, one for one, up to the end
// of the first model, with columns 79-80 (formal charge) blanked, which gemmi
// otherwise rejects in files with old-style identifiers there ("Wrong format
// for charge", bundled 1GRM), and with only the records that hold or group the
// atoms (gemmi 0.5.7 reads some others past their end, or into an overflowing int).
// mmCIF is handled the same way through gemmi's cif::Document and a small
// tokenizer that finds the line of each value of the _atom_site loop; gemmi
// then sees the _atom_site items alone (see keep_atom_site_only()).
#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <map>
#include <string_view>
#include <system_error>
#include <tuple>
#include <utility>
#include <vector>

#include <gemmi/assembly.hpp>
#include <gemmi/cif.hpp>
#include <gemmi/mmcif.hpp>
#include <gemmi/pdb.hpp>

#include "core/errors.h"
#include "core/text_split.h"
#include "geometry/kernel/weighted_point.h"
#include "skin/element_radii.h"
#include "skin/molecule_io_internal.h"

namespace skinmesh::skin::molecule_io_detail {

namespace {

using skinmesh::is_blank;
using skinmesh::split_lines;
using skinmesh::trim;

// Source Lines of gemmi Atoms

/// Where an atom record sits in the text: its line and whether its element came
/// from an element column (PDB columns 77-78, mmCIF type_symbol).
struct SourceRecord {
  int line = 0;
  bool element_from_column = true;
  /// PDB: columns 77-78 held text that is no element symbol (a segment or
  /// serial field that alignment programs write there); the element is then
  /// guessed from the atom name, as with no element column.
  bool column_not_element = false;
  /// PDB: the atom name's four columns 13-16 as the file has them (blank
  /// padded), which place the element symbol by the PDB convention; blank for mmCIF.
  std::array<char, 4> padded_name{' ', ' ', ' ', ' '};
};

/// The element of an atom named `name` by the PDB convention (wwPDB format
/// 3.3, "Atom names"): in the four name columns a one-letter symbol stands in
/// column 14 and a two-letter one in columns 13-14; a digit or blank in column
/// 13 means one letter. Where columns 13-14 spell no element (`CH3 ` of ACE,
/// `OLIN`), the letter in column 13. For a name without its columns (mmCIF;
/// `padded` all blank), the first letter after any digits, or the first two
/// letters if the name is that long only. El::X if none of these is an element.
gemmi::El element_from_name(const std::array<char, 4>& padded, const std::string& name) {
  const auto one = [](char c) { return gemmi::find_element(std::string(1, c).c_str()); };
  const auto two = [](char a, char b) { return gemmi::find_element(std::string{a, b}.c_str()); };
  if (padded != std::array<char, 4>{' ', ' ', ' ', ' '}) {
    if (padded[0] == ' ' || std::isdigit(static_cast<unsigned char>(padded[0]))) return one(padded[1]);
    const gemmi::El e = two(padded[0], padded[1]);
    return e != gemmi::El::X ? e : one(padded[0]);
  }
  std::size_t k = 0;
  while (k < name.size() && std::isdigit(static_cast<unsigned char>(name[k]))) ++k;
  if (k >= name.size()) return gemmi::El::X;
  if (name.size() - k == 2) {
    const gemmi::El e = two(name[k], name[k + 1]);
    if (e != gemmi::El::X) return e;
  }
  return one(name[k]);
}

/// Finds the source record of an atom returned by gemmi. gemmi regroups atoms by
/// chain and residue, so they are matched by exact coordinates (gemmi's fast_float
/// and std::from_chars both round correctly, so they agree on every field that
/// passed parse_double), atom name and altloc; equal keys are served in file order.
/// The records are one array sorted once by key and file order: about 88 bytes
/// per atom and no allocation per atom, which on large files set the reader's
/// time and memory (papers/skin/molecule_io.md, "Reading large files").
class SourceIndex {
 public:
  struct Key {
    std::uint64_t x = 0, y = 0, z = 0;
    std::string name;
    char altloc = '\0';
    friend bool operator<(const Key& a, const Key& b) {
      return std::tie(a.x, a.y, a.z, a.name, a.altloc) < std::tie(b.x, b.y, b.z, b.name, b.altloc);
    }
    friend bool operator==(const Key& a, const Key& b) {
      return std::tie(a.x, a.y, a.z, a.name, a.altloc) == std::tie(b.x, b.y, b.z, b.name, b.altloc);
    }
  };

  static Key key(double x, double y, double z, std::string name, char altloc) {
    return {bits(x), bits(y), bits(z), std::move(name), altloc};
  }
  /// Adds the record of the next atom in file order.
  void add(Key k, SourceRecord r) {
    entries_.push_back({std::move(k), r, static_cast<std::uint32_t>(entries_.size()), false});
    sorted_ = false;
  }
  /// The record of `k` not handed out yet, or {0, true} if there is none.
  SourceRecord take(const Key& k) {
    if (!sorted_) {
      std::sort(entries_.begin(), entries_.end(), [](const Entry& a, const Entry& b) {
        return a.key < b.key || (!(b.key < a.key) && a.order < b.order);
      });
      sorted_ = true;
    }
    auto it =
        std::lower_bound(entries_.begin(), entries_.end(), k, [](const Entry& e, const Key& u) { return e.key < u; });
    for (; it != entries_.end() && it->key == k; ++it)
      if (!it->taken) {
        it->taken = true;
        return it->record;
      }
    return {};
  }

 private:
  struct Entry {
    Key key;
    SourceRecord record;
    std::uint32_t order;  ///< position in the file among the records added
    bool taken;
  };
  /// The bits of `v` (std::bit_cast, spelled for C++17: this file is also built
  /// as C++17 by clang, whose C++20 mode rejects gemmi's cif headers; see
  /// tests/fuzz/CMakeLists.txt).
  static std::uint64_t bits(double v) {
    static_assert(sizeof(double) == sizeof(std::uint64_t));
    std::uint64_t b = 0;
    std::memcpy(&b, &v, sizeof b);
    return b;
  }
  std::vector<Entry> entries_;
  bool sorted_ = true;
};

// PDB Pre-scan

/// True if the record name of `line` is `rec` (case-insensitive, gemmi's rule).
bool record_is(std::string_view line, std::string_view rec) {
  if (line.size() < rec.size()) return false;
  for (std::size_t i = 0; i < rec.size(); ++i)
    if (std::toupper(static_cast<unsigned char>(line[i])) != rec[i]) return false;
  return true;
}

/// The longest line gemmi 0.5.7 reads whole (PdbReadOptions::max_line_length):
/// it drops the rest of a longer line up to a newline, a NUL or a byte >= 0x80,
/// and starts its next line there.
constexpr std::size_t kGemmiLineLength = 120;

/// The refusal of model `model`, listing the file's.
std::string no_model_message(int model, const std::vector<int>& models) {
  std::string list;
  for (std::size_t i = 0; i < models.size() && i < 20; ++i) list += (i ? ", " : "") + std::to_string(models[i]);
  if (models.size() > 20) list += ", ...";
  return "no atoms in model " + std::to_string(model) + " (the file's models: " + list + "; see --model)";
}

/// The PDB pre-scan: the records of the model asked for, and the text gemmi reads.
struct PdbScan {
  SourceIndex index;
  std::string gemmi_text;
};

/// Checks the coordinate columns of every ATOM/HETATM record of the model
/// opt.model (the first if 0; the records of other models become empty lines)
/// and indexes the records by (x, y, z, name, altloc). Writes the text handed to
/// gemmi, line by line (split_lines(): one gemmi line per line of `text`, so
/// gemmi reads exactly the records checked here, and its line numbers are the
/// file's):
/// - every line cut to kGemmiLineLength columns, NUL and CR bytes made blanks
///   (gemmi ends a line, or an atom name, at them);
/// - nothing after the first model (the first ENDMDL after an atom record, or
///   END): gemmi would put the atoms of a later "MODEL n" into its first model
///   when that one was empty and numbered n;
/// - columns 79-80 (the formal charge, unused here) of every ATOM/HETATM record
///   blanked: gemmi rejects the whole file when they hold anything but a
///   charge, and old-style files keep identifiers there (1GRM: columns 73-80
///   read "1GRM 125");
/// - every other record emptied but MODEL, ENDMDL, TER, END and, when
///   opt.assembly names one, REMARK 350 (the assemblies), which gemmi
///   needs to group the atoms, and data_ (an mmCIF file, which gemmi names as
///   such): the reader uses nothing else, and gemmi 0.5.7 parses the rest
///   without care — fixed columns past the end of a short LINK record (columns
///   74-78 of an exact-length copy), DBREF2 numbers of 10 digits into an int
///   (a signed overflow) — and the headers of big files are long.
/// Throws InputError.
PdbScan scan_pdb(const std::string& path, std::string_view text, const ReadOptions& opt) {
  PdbScan scan;
  scan.gemmi_text.reserve(text.size() + 1);
  bool seen_atom = false;
  bool has_models = false;  // a MODEL record met
  int current_model = 0;    // the serial of the last MODEL record
  const std::vector<std::string_view> lines = split_lines(text);
  std::string line;  // one buffer for every line: no allocation per record
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const int line_no = static_cast<int>(k + 1);
    line.assign(lines[k].substr(0, kGemmiLineLength));
    std::replace_if(
        line.begin(), line.end(), [](char c) { return c == '\0' || c == '\r'; }, ' ');
    if (record_is(line, "MODE") && line.rfind("MODEL", 0) == 0) {
      has_models = true;
      current_model = leading_int(std::string_view(line).substr(std::min<std::size_t>(line.size(), 5)));
    }
    // REMARK 350 (the biological assemblies) is kept when one is asked for.
    const bool assembly_remark =
        !opt.assembly.empty() && record_is(line, "REMA") && line.size() > 10 && line.compare(6, 4, " 350") == 0;
    // Another model than the one asked for: an empty line (line numbers stay
    // the file's). The header's REMARK 350 precedes every model.
    if (opt.model != 0 && !assembly_remark && (has_models ? current_model != opt.model : opt.model != 1)) {
      scan.gemmi_text += '\n';
      continue;
    }
    const bool last = (record_is(line, "ENDMDL") && seen_atom) ||                           // gemmi starts model 2
                      (record_is(line, "END") && (line.size() == 3 || is_blank(line[3])));  // gemmi stops
    const bool atom = record_is(line, "ATOM") || record_is(line, "HETA");
    if (!atom && !assembly_remark && !record_is(line, "MODE") && !record_is(line, "END") && !record_is(line, "TER") &&
        !record_is(line, "DATA")) {
      line.clear();
    } else if (atom) {
      seen_atom = true;
      for (std::size_t c = 78; c < std::min<std::size_t>(line.size(), 80); ++c) line[c] = ' ';
      if (line.size() < 54)
        throw InputError(path, line_no,
                         "ATOM/HETATM record too short: x, y, z must fill columns 31-54 (" +
                             std::to_string(lines[k].size()) + " columns found)");
      const std::string_view record = line;
      const double x = parse_number(path, line_no, record.substr(30, 8), "x coordinate");
      const double y = parse_number(path, line_no, record.substr(38, 8), "y coordinate");
      const double z = parse_number(path, line_no, record.substr(46, 8), "z coordinate");
      const std::string name(trim(record.substr(12, 4)));
      const char altloc = line[16] == ' ' ? '\0' : line[16];
      SourceRecord src{line_no, false};
      for (std::size_t c = 12; c < 16 && c < line.size(); ++c) src.padded_name[c - 12] = line[c];
      if (line.size() > 76 && (std::isalpha(static_cast<unsigned char>(line[76])) ||
                               (line.size() > 77 && std::isalpha(static_cast<unsigned char>(line[77]))))) {
        // A column of letters that spell no element: blanked, so that gemmi
        // guesses from the name instead of giving up on the atom.
        const std::string symbol{line[76], line.size() > 77 ? line[77] : ' '};
        src.element_from_column = gemmi::find_element(symbol.c_str()) != gemmi::El::X;
        src.column_not_element = !src.element_from_column;
        if (src.column_not_element)
          for (std::size_t c = 76; c < std::min<std::size_t>(line.size(), 78); ++c) line[c] = ' ';
      }
      scan.index.add(SourceIndex::key(x, y, z, name, altloc), src);
    }
    scan.gemmi_text += line;
    scan.gemmi_text += '\n';  // gemmi counts the newline in a record's length
    if (last) break;
  }
  if (opt.model != 0 && !seen_atom) throw InputError(path, 0, no_model_message(opt.model, pdb_model_numbers(text)));
  return scan;
}

// mmCIF Pre-scan

/// The source line of every value of the loop that starts (keyword "loop_") on
/// 1-based line `loop_line`, for its first `value_count` values; empty if the
/// text does not match (then atom lines stay unknown). CIF 1.1 tokens: blank
/// separated, '#' comments, '...' and "..." quoted strings ending at a quote
/// followed by a blank, and ;-delimited text fields.
std::vector<int> loop_value_lines(std::string_view text, int loop_line, std::size_t value_count) {
  std::vector<int> lines;
  std::size_t pos = 0;
  int line = 1;
  while (line < loop_line && pos < text.size()) {
    const std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) return {};
    pos = nl + 1;
    ++line;
  }
  enum class Stage { Keyword, Tags, Values } stage = Stage::Keyword;
  bool line_start = true;
  while (pos < text.size() && lines.size() < value_count) {
    const char c = text[pos];
    if (c == '\n') {
      ++line;
      ++pos;
      line_start = true;
      continue;
    }
    if (is_blank(c)) {
      ++pos;
      line_start = false;
      continue;
    }
    if (c == '#') {
      pos = text.find('\n', pos);
      if (pos == std::string_view::npos) break;
      continue;
    }
    const int token_line = line;
    std::size_t end = pos;
    bool quoted = false;
    if (c == ';' && line_start) {  // text field up to a line starting with ';'
      std::size_t close = text.find("\n;", pos);
      if (close == std::string_view::npos) return {};
      line += static_cast<int>(std::count(text.begin() + static_cast<std::ptrdiff_t>(pos),
                                          text.begin() + static_cast<std::ptrdiff_t>(close + 1), '\n'));
      end = close + 2;
      quoted = true;
    } else if (c == '\'' || c == '"') {
      end = pos + 1;
      while (end < text.size() && text[end] != '\n' &&
             !(text[end] == c && (end + 1 == text.size() || is_blank(text[end + 1]))))
        ++end;
      if (end < text.size() && text[end] == c) ++end;
      quoted = true;
    } else {
      while (end < text.size() && !is_blank(text[end])) ++end;
    }
    const std::string_view token = text.substr(pos, end - pos);
    pos = end;
    line_start = false;
    if (stage == Stage::Keyword) {
      if (lowercase(token) != "loop_") return {};
      stage = Stage::Tags;
      continue;
    }
    if (stage == Stage::Tags && !quoted && token.front() == '_') continue;
    stage = Stage::Values;
    lines.push_back(token_line);
  }
  if (lines.size() != value_count) return {};
  return lines;
}

/// True if the leading integer of `v` — after white space and a sign, as gemmi's
/// string_to_int() and no_sign_atoi() read it — has a magnitude above INT_MAX.
bool leading_int_overflows(std::string_view v) {
  std::size_t i = 0;
  while (i < v.size() && gemmi::is_space(v[i])) ++i;
  if (i < v.size() && (v[i] == '-' || v[i] == '+')) ++i;
  std::size_t end = i;
  while (end < v.size() && gemmi::is_digit(v[end])) ++end;
  int magnitude = 0;
  return std::from_chars(v.data() + i, v.data() + end, magnitude).ec == std::errc::result_out_of_range;
}

/// Adds to the _atom_site loop of `block` the items gemmi 0.5.7 requires but a
/// valid minimal mmCIF may leave out (PyMOL writes no auth_seq_id, other tools
/// no label_alt_id, occupancy or B factor): without one of them gemmi finds no
/// atom table at all. Each is filled as the mmCIF dictionary reads its absence:
/// id the row number, type_symbol '?' (the element is then guessed from the
/// atom name), label_alt_id '.', label_asym_id the auth_asym_id (else '.'),
/// occupancy 1, B_iso_or_equiv 0, auth_seq_id the label_seq_id (else '?').
/// Returns the names of the items added. A loop without Cartn_x/y/z is left
/// alone (the atoms have no positions).
std::vector<std::string> complete_atom_site(gemmi::cif::Block& block) {
  std::vector<std::string> added;
  for (gemmi::cif::Item& item : block.items) {
    if (item.type != gemmi::cif::ItemType::Loop || item.loop.tags.empty() ||
        !gemmi::istarts_with(item.loop.tags.front(), "_atom_site."))
      continue;
    gemmi::cif::Loop& loop = item.loop;
    if (!loop.has_tag("_atom_site.Cartn_x") || !loop.has_tag("_atom_site.Cartn_y") ||
        !loop.has_tag("_atom_site.Cartn_z"))
      return added;
    const std::size_t rows = loop.length(), width = loop.width();
    // Each missing item: its name and its value in row r.
    std::vector<std::pair<std::string, std::function<std::string(std::size_t)>>> missing;
    const auto copy_of = [&loop, width](const char* tag, const char* otherwise) {
      const int c = loop.find_tag(tag);
      return [&loop, width, c, otherwise](std::size_t r) {
        return c >= 0 ? loop.values[r * width + static_cast<std::size_t>(c)] : std::string(otherwise);
      };
    };
    const auto constant = [](const char* v) { return [v](std::size_t) { return std::string(v); }; };
    const auto need = [&](const char* name, std::function<std::string(std::size_t)> value) {
      if (!loop.has_tag(std::string("_atom_site.") + name)) missing.emplace_back(name, std::move(value));
    };
    need("id", [](std::size_t r) { return std::to_string(r + 1); });
    need("type_symbol", constant("?"));
    need("label_alt_id", constant("."));
    need("label_asym_id", copy_of("_atom_site.auth_asym_id", "."));
    need("occupancy", constant("1"));
    need("B_iso_or_equiv", constant("0"));
    need("auth_seq_id", copy_of("_atom_site.label_seq_id", "?"));
    if (missing.empty()) return added;
    std::vector<std::string> values;
    values.reserve(rows * (width + missing.size()));
    std::vector<std::string> extra(missing.size());
    for (std::size_t r = 0; r < rows; ++r) {
      for (std::size_t k = 0; k < missing.size(); ++k) extra[k] = missing[k].second(r);  // before the row moves
      for (std::size_t c = 0; c < width; ++c) values.push_back(std::move(loop.values[r * width + c]));
      for (std::string& v : extra) values.push_back(std::move(v));
    }
    for (const auto& m : missing) {
      loop.tags.push_back("_atom_site." + m.first);
      added.push_back(m.first);
    }
    loop.values = std::move(values);
    return added;
  }
  return added;
}

/// Prepares `block` for gemmi::make_structure(), which reads all of it: erases
/// every item but the _atom_site ones (the only category read_molecule() uses;
/// gemmi 0.5.7 parses the integers of the others without overflow checks,
/// undefined behaviour on a long digit string), and replaces by '?' (absent,
/// read as 0) every value of the _atom_site integer items gemmi reads (id,
/// label_seq_id, auth_seq_id, pdbx_formal_charge, pdbx_tls_group_id) whose
/// leading integer is beyond ±INT_MAX — as leading_int() reads such serials and
/// residue numbers in PQR.
std::vector<std::string> keep_atom_site_only(gemmi::cif::Block& block, bool keep_assemblies) {
  for (gemmi::cif::Item& item : block.items)
    if (!item.has_prefix("_atom_site.") && !(keep_assemblies && (item.has_prefix("_pdbx_struct_assembly.") ||
                                                                 item.has_prefix("_pdbx_struct_assembly_gen.") ||
                                                                 item.has_prefix("_pdbx_struct_oper_list."))))
      item.erase();
  const std::vector<std::string> added = complete_atom_site(block);
  // The table gemmi reads atoms from: the item of _atom_site.id (a tag appears
  // once per block: gemmi's parser rejects duplicates).
  gemmi::cif::Table table =
      block.find("_atom_site.", {"id", "?label_seq_id", "?auth_seq_id", "?pdbx_formal_charge", "?pdbx_tls_group_id"});
  if (!table.ok()) return added;
  for (std::size_t r = 0; r < table.length(); ++r) {
    gemmi::cif::Table::Row row = table[static_cast<int>(r)];
    for (std::size_t c = 0; c < row.size(); ++c)
      if (row.has(c) && leading_int_overflows(row[c])) row[c] = "?";
  }
  return added;
}

/// Checks Cartn_x/y/z of every _atom_site row of model `model` (0: the first; CIF numbers,
/// an esd suffix "(n)" allowed) and indexes the rows like scan_pdb(). The first
/// block is the one gemmi::make_structure() reads. Throws InputError.
SourceIndex scan_mmcif(const std::string& path, std::string_view text, gemmi::cif::Block& block, int model) {
  SourceIndex index;
  enum { kX, kY, kZ, kAuthAtom, kLabelAtom, kAlt, kModel, kType };
  gemmi::cif::Table table =
      block.find("_atom_site.", {"Cartn_x", "Cartn_y", "Cartn_z", "?auth_atom_id", "?label_atom_id", "?label_alt_id",
                                 "?pdbx_PDB_model_num", "?type_symbol"});
  if (!table.ok() || table.length() == 0) return index;
  std::vector<int> value_lines;
  if (table.loop_item != nullptr) {
    const gemmi::cif::Loop& loop = table.loop_item->loop;
    value_lines = loop_value_lines(text, table.loop_item->line_number, loop.values.size());
  }
  const std::size_t width = table.loop_item != nullptr ? table.loop_item->loop.width() : 0;
  auto line_of = [&](std::size_t row, int column) -> int {
    const int pos = table.positions.at(static_cast<std::size_t>(column));
    if (value_lines.empty() || pos < 0) return 0;
    return value_lines.at(row * width + static_cast<std::size_t>(pos));
  };
  auto number = [&](std::size_t row, int column, const char* what) {
    std::string_view v = table[static_cast<int>(row)][static_cast<std::size_t>(column)];
    // A CIF number may carry its standard uncertainty: "12.345(6)".
    if (v.size() > 2 && v.back() == ')') {
      const std::size_t open = v.rfind('(');
      if (open != std::string_view::npos && open > 0 &&
          std::all_of(v.begin() + static_cast<std::ptrdiff_t>(open + 1), v.end() - 1,
                      [](char ch) { return std::isdigit(static_cast<unsigned char>(ch)) != 0; }))
        v = v.substr(0, open);
    }
    return parse_number(path, line_of(row, column), v, what);
  };
  const int name_column = table.first_of(kAuthAtom, kLabelAtom);
  // The model kept: the first row's, or the one asked for (a file without
  // model numbers holds model 1).
  std::string kept_model;
  std::size_t kept_rows = 0;
  for (std::size_t r = 0; r < table.length(); ++r) {
    gemmi::cif::Table::Row row = table[static_cast<int>(r)];
    if (row.has(kModel)) {
      const std::string row_model = gemmi::cif::as_string(row[kModel]);
      if (r == 0 && model == 0) kept_model = row_model;
      if (model != 0 ? leading_int(row_model) != model : row_model != kept_model) continue;
    } else if (model > 1) {
      continue;
    }
    ++kept_rows;
    const double x = number(r, kX, "x coordinate");
    const double y = number(r, kY, "y coordinate");
    const double z = number(r, kZ, "z coordinate");
    const std::string name = row.has(static_cast<std::size_t>(name_column))
                                 ? gemmi::cif::as_string(row[static_cast<std::size_t>(name_column)])
                                 : std::string();
    const char altloc = row.has(kAlt) ? gemmi::cif::as_char(row[kAlt], '\0') : '\0';
    index.add(SourceIndex::key(x, y, z, name, altloc), {line_of(r, kX), row.has(kType)});
  }
  if (model != 0 && kept_rows == 0)
    throw InputError(path, 0, no_model_message(model, mmcif_model_numbers(path, std::string(text))));
  return index;
}

// gemmi Structure to Molecule

/// Where an atom of the model came from: what assemblies name.
struct AtomOrigin {
  std::string chain;     ///< the chain's name (PDB assemblies name chains)
  std::string subchain;  ///< label_asym_id (mmCIF assemblies name these)
};

/// The atoms of the biological assembly `id` of `st`: every generator's
/// operators applied, in order, to the atoms of the chains or subchains it
/// names (`origin`, one per atom). A chain copied more than once gets its
/// copy's number after its name from the second copy on ("A", "A2", "A3"),
/// as gemmi names them. Throws InputError for an unknown id, an assembly that
/// holds no atom read, or a copy outside ±geometry::kMaxCoordinate.
std::vector<Atom> expand_assembly(const std::string& path, const gemmi::Structure& st, const std::string& id,
                                  const std::vector<Atom>& atoms, const std::vector<AtomOrigin>& origin,
                                  std::vector<std::string>& notes) {
  const gemmi::Assembly* assembly = nullptr;
  std::string names;
  for (const gemmi::Assembly& a : st.assemblies) {
    names += (names.empty() ? "" : ", ") + a.name;
    if (a.name == id) assembly = &a;
  }
  if (assembly == nullptr)
    throw InputError(path, 0,
                     names.empty() ? "no assembly " + id +
                                         ": the file lists none (PDB REMARK 350 BIOMOLECULE, mmCIF "
                                         "_pdbx_struct_assembly); mesh the file's coordinates without --assembly"
                                   : "no assembly " + id + " (the file lists: " + names + ")");
  std::vector<Atom> out;
  std::map<std::string, int> copies;  // per chain, the copies made
  std::size_t operators = 0;
  for (const gemmi::Assembly::Gen& gen : assembly->generators) {
    const bool all = !gen.chains.empty() && gen.chains.front() == "(all)";
    for (const gemmi::Assembly::Operator& op : gen.operators) {
      ++operators;
      std::map<std::string, std::string> named;  // chain -> its name in this copy
      for (std::size_t i = 0; i < atoms.size(); ++i) {
        const AtomOrigin& o = origin[i];
        const bool in = all || std::find(gen.chains.begin(), gen.chains.end(), o.chain) != gen.chains.end() ||
                        std::find(gen.subchains.begin(), gen.subchains.end(), o.subchain) != gen.subchains.end();
        if (!in) continue;
        auto [it, fresh] = named.emplace(o.chain, std::string());
        if (fresh) {
          const int k = ++copies[o.chain];
          it->second = k == 1 ? o.chain : o.chain + std::to_string(k);
        }
        Atom a = atoms[i];
        const gemmi::Vec3 p = op.transform.apply(gemmi::Vec3(a.centre.x(), a.centre.y(), a.centre.z()));
        a.centre = Vec3(p.x, p.y, p.z);
        for (int c = 0; c < 3; ++c)
          if (!(std::abs(a.centre[c]) <= geometry::kMaxCoordinate))
            throw InputError(path, a.line,
                             "assembly " + id + ": operator " + op.name + " moves " + a.name +
                                 " outside the supported range of coordinates");
        a.chain = it->second;
        out.push_back(std::move(a));
      }
    }
  }
  if (out.empty())
    throw InputError(path, 0, "assembly " + id + " holds none of the atoms read (its chains are not in the model)");
  notes.push_back("assembly " + id + ": " + std::to_string(operators) +
                  (operators == 1 ? " operator, " : " operators, ") + std::to_string(out.size()) +
                  " atoms from the model's " + std::to_string(atoms.size()));
  return out;
}

/// The atoms of model opt.model of `st` (the first if 0), filtered and given
/// Bondi radii; the assembly opt.assembly if one is named.
Molecule from_structure(const std::string& path, const gemmi::Structure& st, SourceIndex& index, const ReadOptions& opt,
                        const std::vector<std::string>& reader_notes = {}) {
  std::vector<Atom> atoms;
  NoteList notes(path);
  for (const std::string& n : reader_notes) notes.add(0, n);
  if (st.models.empty()) return finish(path, std::move(atoms), notes);
  // The pre-scans handed gemmi the model asked for (PDB), or indexed its rows
  // (mmCIF, where gemmi makes every model): that model, else the first.
  const gemmi::Model* chosen = &st.models.front();
  for (const gemmi::Model& m : st.models)
    if (opt.model != 0 && leading_int(m.name) == opt.model) chosen = &m;
  const gemmi::Model& model = *chosen;
  std::vector<AtomOrigin> origin;  // per atom kept: its chain and subchain, for the assembly

  // First alternate location: per residue position (chain, number, insertion
  // code) and per atom of it, the first altloc letter met.
  using Position = std::tuple<std::string, int, char>;
  using AtomSlot = std::tuple<std::string, int, char, std::string>;
  std::map<Position, char> position_first;
  std::map<AtomSlot, char> atom_first;
  int guessed_elements = 0, not_elements = 0;
  std::string first_not_element;
  char fallback_buf[32];
  std::snprintf(fallback_buf, sizeof fallback_buf, "%.2f", kFallbackRadius);
  const std::string fallback_text = fallback_buf;

  for (const gemmi::Chain& chain : model.chains) {
    for (const gemmi::Residue& res : chain.residues) {
      const int resnum = res.seqid.num.has_value() ? res.seqid.num.value : 0;
      const Position position{chain.name, resnum, res.seqid.icode};
      const bool water = res.is_water() || is_water_residue(res.name);

      // A residue whose atoms all carry one altloc letter that is not the first
      // letter of its position is an alternative residue (micro-heterogeneity).
      char residue_letter = '\0';
      bool single_letter = !res.atoms.empty();
      for (const gemmi::Atom& a : res.atoms) {
        if (a.altloc == '\0' || (residue_letter != '\0' && a.altloc != residue_letter)) {
          single_letter = false;
          break;
        }
        residue_letter = a.altloc;
      }
      bool skip_residue = false;
      if (single_letter) {
        auto [it, inserted] = position_first.emplace(position, residue_letter);
        skip_residue = !inserted && it->second != residue_letter;
      }

      for (const gemmi::Atom& a : res.atoms) {
        const SourceRecord src = index.take(SourceIndex::key(a.pos.x, a.pos.y, a.pos.z, a.name, a.altloc));
        // Named only for a note or an error: most atoms get neither.
        const auto who = [&] { return describe(a.name, res.name, chain.name, resnum); };
        if (skip_residue) {
          notes.add(src.line, "alternate location " + std::string(1, a.altloc) + " of " + who() +
                                  " skipped (alternative residue; location " +
                                  std::string(1, position_first[position]) + " kept)");
          continue;
        }
        if (a.altloc != '\0') {
          position_first.emplace(position, a.altloc);
          auto [it, inserted] = atom_first.emplace(AtomSlot{chain.name, resnum, res.seqid.icode, a.name}, a.altloc);
          if (!inserted && it->second != a.altloc) {
            notes.add(src.line, "alternate location " + std::string(1, a.altloc) + " of " + who() +
                                    " skipped (location " + std::string(1, it->second) + " kept)");
            continue;
          }
        }
        if (water && !opt.keep_water) {
          notes.add(src.line, "water " + res.name + " " + std::to_string(resnum) + " skipped (use --keep-water)");
          continue;
        }
        gemmi::Element element = a.element;
        if (element == gemmi::El::X && !src.element_from_column) element = element_from_name(src.padded_name, a.name);
        if (element == gemmi::El::X) {
          throw InputError(path, src.line,
                           "unknown element for " + who() +
                               (src.element_from_column
                                    ? " (element column not recognised; write the element symbol in it)"
                                    : " (no element column, and none recognised in the atom name; write the element "
                                      "symbol in columns 77-78)"));
        }
        if (element.is_hydrogen() && !opt.keep_hydrogens) {
          notes.add(src.line, "hydrogen " + who() + " skipped (hydrogens not kept)");
          continue;
        }
        Atom atom;
        atom.centre = Vec3(a.pos.x, a.pos.y, a.pos.z);
        atom.element = canonical_element_symbol(element.name());
        const VanDerWaalsRadius r = van_der_waals_radius(atom.element);
        atom.radius = r.radius;
        if (!r.from_bondi)
          notes.add(src.line,
                    "no Bondi radius for element " + atom.element + " (" + who() + "); using " + fallback_text + " A");
        atom.name = a.name;
        atom.residue = res.name;
        atom.chain = chain.name;
        atom.residue_number = resnum;
        atom.insertion_code = res.seqid.icode == '\0' || res.seqid.icode == '?' ? ' ' : res.seqid.icode;
        atom.serial = a.serial;
        atom.line = src.line;
        if (src.column_not_element) {
          if (not_elements++ == 0) first_not_element = "line " + std::to_string(src.line) + ", atom " + a.name;
        } else if (!src.element_from_column) {
          ++guessed_elements;
        }
        atoms.push_back(std::move(atom));
        if (!opt.assembly.empty()) origin.push_back({chain.name, res.subchain});
      }
    }
  }
  if (guessed_elements > 0)
    notes.add(0, std::to_string(guessed_elements) + " atoms have no element column; elements guessed from atom names");
  if (not_elements > 0)
    notes.add(0, std::to_string(not_elements) + " atoms have text that is no element symbol in columns 77-78 (first: " +
                     first_not_element + "); elements guessed from atom names");
  if (opt.assembly.empty()) return finish(path, std::move(atoms), notes);
  // finish() orders the atoms by line; the origins go with them.
  if (std::all_of(atoms.begin(), atoms.end(), [](const Atom& a) { return a.line > 0; })) {
    std::vector<std::size_t> order(atoms.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return atoms[a].line < atoms[b].line; });
    std::vector<Atom> sorted_atoms;
    std::vector<AtomOrigin> sorted_origin;
    for (std::size_t i : order) sorted_atoms.push_back(std::move(atoms[i])), sorted_origin.push_back(origin[i]);
    atoms.swap(sorted_atoms);
    origin.swap(sorted_origin);
  }
  Molecule mol = finish(path, std::move(atoms), notes);
  mol.atoms = expand_assembly(path, st, opt.assembly, mol.atoms, origin, mol.notes);
  return mol;
}

/// gemmi reports "Problem in line N: ..." for some PDB errors; recover N.
int gemmi_line(const std::string& what) {
  static constexpr std::string_view kPrefix = "Problem in line ";
  const std::size_t at = what.find(kPrefix);
  if (at == std::string::npos) return 0;
  return leading_int(std::string_view(what).substr(at + kPrefix.size()));
}

}  // namespace

Molecule read_pdb(const std::string& path, const std::string& text, const ReadOptions& opt) {
  PdbScan scan = scan_pdb(path, text, opt);
  gemmi::Structure st;
  try {
    st = gemmi::read_pdb_string(scan.gemmi_text, path);
  } catch (const std::exception& e) {
    throw InputError(path, gemmi_line(e.what()), std::string("PDB: ") + e.what());
  }
  std::string().swap(scan.gemmi_text);  // a copy of the file: not needed while the atoms are made
  return from_structure(path, st, scan.index, opt);
}

Molecule read_mmcif(const std::string& path, const std::string& text, const ReadOptions& opt) {
  gemmi::Structure st;
  SourceIndex index;
  std::vector<std::string> reader_notes;
  try {
    gemmi::cif::Document doc = gemmi::cif::read_memory(text.data(), text.size(), path.c_str());
    if (doc.blocks.empty()) throw InputError(path, 0, "no atoms found (no data block)");
    std::string added;
    for (const std::string& tag : keep_atom_site_only(doc.blocks.front(), !opt.assembly.empty()))
      added += (added.empty() ? "" : ", ") + tag;
    if (!added.empty())
      reader_notes.push_back("_atom_site has no " + added + " (read as absent values: a minimal mmCIF)");
    index = scan_mmcif(path, text, doc.blocks.front(), opt.model);
    st = gemmi::make_structure(doc);
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(path, 0, std::string("mmCIF: ") + e.what());
  }
  return from_structure(path, st, index, opt, reader_notes);
}

std::vector<int> pdb_model_numbers(std::string_view text) {
  std::vector<int> models;
  for (const std::string_view line : split_lines(text))
    if (line.size() >= 5 && line.substr(0, 5) == "MODEL")
      models.push_back(leading_int(line.substr(5, std::min<std::size_t>(line.size(), 14) - 5)));
  if (models.empty()) models.push_back(1);
  return models;
}

std::vector<int> mmcif_model_numbers(const std::string& path, const std::string& text) {
  std::vector<int> models;
  try {
    gemmi::cif::Document doc = gemmi::cif::read_memory(text.data(), text.size(), path.c_str());
    if (!doc.blocks.empty()) {
      std::string last;
      for (const auto row : doc.blocks.front().find("_atom_site.", {"pdbx_PDB_model_num"})) {
        const std::string m = gemmi::cif::as_string(row[0]);
        if (m == last) continue;
        last = m;
        const int n = leading_int(m);
        if (std::find(models.begin(), models.end(), n) == models.end()) models.push_back(n);
      }
    }
  } catch (const std::exception& e) {
    throw InputError(path, 0, std::string("mmCIF: ") + e.what());
  }
  if (models.empty()) models.push_back(1);
  return models;
}

}  // namespace skinmesh::skin::molecule_io_detail

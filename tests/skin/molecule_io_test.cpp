// tests/skin/molecule_io_test.cpp: read_molecule() on the bundled molecules (atom
// counts from data/README.md) and on small broken files written by the tests.
#include <doctest/doctest.h>
#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/errors.h"
#include "skin/element_radii.h"
#include "skin/molecule_io.h"

namespace {

using skinmesh::InputError;
using skinmesh::skin::Molecule;
using skinmesh::skin::read_molecule;
using skinmesh::skin::read_molecule_from_string;
using skinmesh::skin::ReadOptions;

std::string data_file(const std::string& name) { return std::string(SKINMESH_DATA) + "/" + name; }

/// A scratch directory for this test run, removed at exit.
struct ScratchDir {
  std::filesystem::path dir;
  ScratchDir() {
    dir = std::filesystem::temp_directory_path() /
          ("skinmesh_molecule_io_test_" + std::to_string(std::random_device{}()));
    std::filesystem::create_directories(dir);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir, ec);
  }
  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = (dir / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
};

const ScratchDir& scratch() {
  static const ScratchDir d;
  return d;
}

/// One fixed-column PDB ATOM/HETATM record (columns as in the PDB v3.3 spec).
std::string pdb_atom(const char* record, int serial, const char* name, char altloc, const char* res, const char* chain,
                     int resnum, const char* x, const char* y, const char* z, const char* element) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%-6s%5d %-4s%c%3s %1s%4d    %8s%8s%8s%6.2f%6.2f          %2s", record, serial, name,
                altloc, res, chain, resnum, x, y, z, 1.0, 10.0, element);
  return std::string(buf) + "\n";
}

/// The InputError thrown by read_molecule(path, opt); fails the test if none.
InputError error_of(const std::string& path, const ReadOptions& opt = {}) {
  try {
    read_molecule(path, opt);
  } catch (const InputError& e) {
    return e;
  }
  FAIL("no InputError for " << path);
  return InputError(path, 0, "unreachable");
}

/// The InputError thrown by read_molecule_from_string(text, name); fails the test if none.
InputError string_error_of(const std::string& text, const std::string& name) {
  try {
    read_molecule_from_string(text, name);
  } catch (const InputError& e) {
    return e;
  }
  FAIL("no InputError for " << name);
  return InputError(name, 0, "unreachable");
}

std::size_t count_notes_containing(const Molecule& m, const std::string& s) {
  std::size_t n = 0;
  for (const std::string& note : m.notes) n += note.find(s) != std::string::npos;
  return n;
}

}  // namespace

TEST_SUITE("skin") {

TEST_CASE("element radii: Bondi values, deuterium, fallback, symbols") {
  using namespace skinmesh::skin;
  CHECK(bondi_radius("H") == 1.20);
  CHECK(bondi_radius("C") == 1.70);
  CHECK(bondi_radius("N") == 1.55);
  CHECK(bondi_radius("O") == 1.52);
  CHECK(bondi_radius("F") == 1.47);
  CHECK(bondi_radius("P") == 1.80);
  CHECK(bondi_radius("S") == 1.80);
  CHECK(bondi_radius("CL") == 1.75);
  CHECK(bondi_radius(" Br") == 1.85);
  CHECK(bondi_radius("i") == 1.98);
  CHECK(bondi_radius("Se") == 1.90);
  CHECK(bondi_radius("Zn") == 1.39);
  CHECK(bondi_radius("U") == 1.86);
  CHECK(bondi_radius("D") == 1.20);
  for (const char* metal : {"Fe", "Ca", "Mn", "Co", "Mo"}) {
    CHECK_FALSE(bondi_radius(metal).has_value());
    const VanDerWaalsRadius r = van_der_waals_radius(metal);
    CHECK(r.radius == kFallbackRadius);
    CHECK_FALSE(r.from_bondi);
  }
  CHECK(van_der_waals_radius("cl").from_bondi);
  CHECK(canonical_element_symbol("CL") == "Cl");
  CHECK(canonical_element_symbol(" fe ") == "Fe");
  CHECK(canonical_element_symbol("Og") == "Og");
  CHECK(canonical_element_symbol("XX").empty());
  CHECK(canonical_element_symbol("").empty());
}

TEST_CASE("read_molecule: bundled molecules have the documented atom counts") {
  // data/README.md: total ATOM/HETATM records, minus waters by default.
  const std::map<std::string, std::size_t> expected = {
      {"ligand_2zmm.pdb", 31},
      {"ligand_1hpv_amprenavir.pdb", 35},
      {"ligand_1hvr_xk263.pdb", 46},
      {"gramicidinA_1grm_model1.pdb", 272},
      {"crambin_1crn.pdb", 327},
      {"adna_3dna_fiber_30bp.pdb", 1230},
      {"hivprotease_xk263_1hvr.pdb", 1890},
      {"src_kinase_2src.pdb", 3915 - 269},
  };
  for (const auto& [name, count] : expected) {
    CAPTURE(name);
    const Molecule m = read_molecule(data_file(name));
    CHECK(m.source == data_file(name));
    CHECK(m.atoms.size() == count);
    int previous_line = 0;
    for (const auto& a : m.atoms) {
      CHECK(a.line > previous_line);  // file order, every line known
      previous_line = a.line;
      CHECK(std::isfinite(a.centre.x()));
      CHECK(a.radius > 0.0);
      // PDB radii are Bondi's, by element.
      REQUIRE(skinmesh::skin::bondi_radius(a.element).has_value());
      CHECK(a.radius == *skinmesh::skin::bondi_radius(a.element));
    }
  }
}

TEST_CASE("read_molecule: crambin PDB atoms, identifiers and radii") {
  const Molecule m = read_molecule(data_file("crambin_1crn.pdb"));
  REQUIRE(m.atoms.size() == 327);
  const auto& first = m.atoms.front();
  // ATOM      1  N   THR A   1      17.047  14.099   3.625  1.00 13.79           N
  CHECK(first.centre == skinmesh::Vec3(17.047, 14.099, 3.625));
  CHECK(first.element == "N");
  CHECK(first.radius == 1.55);
  CHECK(first.name == "N");
  CHECK(first.residue == "THR");
  CHECK(first.chain == "A");
  CHECK(first.residue_number == 1);
  CHECK(first.serial == 1);
  std::map<std::string, int> by_element;
  for (const auto& a : m.atoms) ++by_element[a.element];
  CHECK(by_element == std::map<std::string, int>{{"C", 202}, {"N", 55}, {"O", 64}, {"S", 6}});
  for (const auto& a : m.atoms) {
    if (a.element == "C") CHECK(a.radius == 1.70);
    if (a.element == "O") CHECK(a.radius == 1.52);
    if (a.element == "S") CHECK(a.radius == 1.80);
  }
  CHECK(m.notes.empty());
}

TEST_CASE("read_molecule: 3DNA A-DNA without element column gets C/N/O/P from atom names") {
  const Molecule m = read_molecule(data_file("adna_3dna_fiber_30bp.pdb"));
  REQUIRE(m.atoms.size() == 1230);
  std::map<std::string, int> by_element;
  for (const auto& a : m.atoms) ++by_element[a.element];
  // Atom names (data/README.md): P O1P O2P O5' C5' ... 60 P, and no other elements.
  CHECK(by_element.size() == 4);
  CHECK(by_element["P"] == 60);
  CHECK(by_element["C"] + by_element["N"] + by_element["O"] + by_element["P"] == 1230);
  for (const auto& a : m.atoms) {
    if (a.name == "O1P" || a.name == "O2P" || a.name == "O5'") CHECK(a.element == "O");
    if (a.name == "C5'" || a.name == "C5M") CHECK(a.element == "C");
    if (a.name == "N9") CHECK(a.element == "N");
  }
  CHECK(count_notes_containing(m, "elements guessed from atom names") == 1);
  // the 3DNA rows in this file are exactly 54 characters long (no occupancy)
  CHECK(m.atoms.front().centre == skinmesh::Vec3(3.063, 8.025, -4.135));
}

TEST_CASE("read_molecule: waters excluded by default, kept on demand (2SRC, 269 waters)") {
  const Molecule dry = read_molecule(data_file("src_kinase_2src.pdb"));
  CHECK(dry.atoms.size() == 3646);
  CHECK(dry.notes.size() == 269);
  CHECK(count_notes_containing(dry, "water HOH") == 269);
  for (const auto& a : dry.atoms) CHECK(a.residue != "HOH");
  // the note names the file and the line of the record
  CHECK(dry.notes.front().rfind(data_file("src_kinase_2src.pdb") + ":", 0) == 0);

  ReadOptions wet;
  wet.keep_water = true;
  const Molecule m = read_molecule(data_file("src_kinase_2src.pdb"), wet);
  CHECK(m.atoms.size() == 3915);
  CHECK(m.notes.empty());
  std::size_t waters = 0;
  for (const auto& a : m.atoms) waters += a.residue == "HOH";
  CHECK(waters == 269);
}

TEST_CASE("read_molecule: hydrogens kept by default, dropped on demand (1HVR, 330 H)") {
  const Molecule with_h = read_molecule(data_file("hivprotease_xk263_1hvr.pdb"));
  std::size_t h = 0;
  for (const auto& a : with_h.atoms) h += a.element == "H";
  CHECK(h == 330);
  for (const auto& a : with_h.atoms)
    if (a.element == "H") CHECK(a.radius == 1.20);

  ReadOptions opt;
  opt.keep_hydrogens = false;
  const Molecule heavy = read_molecule(data_file("hivprotease_xk263_1hvr.pdb"), opt);
  CHECK(heavy.atoms.size() == 1560);
  CHECK(count_notes_containing(heavy, "hydrogen") == 330);
}

TEST_CASE("read_molecule: crambin PQR takes radii from the file, skips zero-radius hydrogens") {
  const Molecule m = read_molecule(data_file("crambin_1crn.pqr"));
  // 642 records (data/README.md) = 406 atoms kept + 236 hydrogens of radius 0.
  CHECK(m.atoms.size() == 406);
  CHECK(m.notes.size() == 236);
  CHECK(m.atoms.size() + m.notes.size() == 642);
  CHECK(count_notes_containing(m, "has radius 0; skipped") == 236);
  // ATOM      1  N   THR     1      17.047  14.099   3.625 -0.3200 2.0000
  const auto& first = m.atoms.front();
  CHECK(first.centre == skinmesh::Vec3(17.047, 14.099, 3.625));
  CHECK(first.radius == 2.0);
  CHECK(first.element == "N");
  CHECK(first.residue == "THR");
  CHECK(first.chain.empty());
  CHECK(first.residue_number == 1);
  CHECK(first.line == 8);  // after 7 REMARK lines
  const std::set<double> parse_radii = {1.0, 1.4, 1.5, 1.7, 1.85, 2.0};
  std::size_t hydrogens = 0;
  for (const auto& a : m.atoms) {
    CHECK(parse_radii.count(a.radius) == 1);
    hydrogens += a.element == "H";
  }
  CHECK(hydrogens == 642 - 327 - 236);
  // radii from the file differ from Bondi's: the first carbon (CA) has 2.0, not 1.70
  CHECK(m.atoms[1].name == "CA");
  CHECK(m.atoms[1].radius == 2.0);
}

TEST_CASE("read_molecule: mmCIF gives the same atoms as PDB, with line numbers") {
  const Molecule pdb = read_molecule(data_file("crambin_1crn.pdb"));
  std::ostringstream cif;
  cif << "data_1CRN\n#\nloop_\n"
         "_atom_site.group_PDB\n_atom_site.id\n_atom_site.type_symbol\n_atom_site.label_atom_id\n"
         "_atom_site.label_alt_id\n_atom_site.label_comp_id\n_atom_site.label_asym_id\n"
         "_atom_site.label_seq_id\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n_atom_site.Cartn_z\n"
         "_atom_site.occupancy\n_atom_site.B_iso_or_equiv\n_atom_site.auth_seq_id\n"
         "_atom_site.pdbx_PDB_model_num\n";
  char buf[256];
  for (const auto& a : pdb.atoms) {
    std::snprintf(buf, sizeof buf, "ATOM %d %s %s . %s %s %d %.3f %.3f %.3f 1.00 10.00 %d 1\n", a.serial,
                  a.element.c_str(), a.name.c_str(), a.residue.c_str(), a.chain.c_str(), a.residue_number, a.centre.x(),
                  a.centre.y(), a.centre.z(), a.residue_number);
    cif << buf;
  }
  // a second model that must be ignored
  cif << "ATOM 9999 C CA . THR A 1 0.000 0.000 0.000 1.00 10.00 1 2\n#\n";
  const std::string path = scratch().write("crambin.cif", cif.str());
  const Molecule m = read_molecule(path);
  REQUIRE(m.atoms.size() == pdb.atoms.size());
  for (std::size_t i = 0; i < m.atoms.size(); ++i) {
    CHECK(m.atoms[i].centre == pdb.atoms[i].centre);
    CHECK(m.atoms[i].radius == pdb.atoms[i].radius);
    CHECK(m.atoms[i].name == pdb.atoms[i].name);
    CHECK(m.atoms[i].line == static_cast<int>(i) + 19);  // 18 header lines
  }

  // a bad coordinate is reported at its line
  std::string text = cif.str();
  const std::size_t at = text.find(" 17.047 ");
  REQUIRE(at != std::string::npos);
  text.replace(at, 8, " 17.0x7 ");
  const InputError e = error_of(scratch().write("bad.cif", text));
  CHECK(e.line() == 19);
  CHECK(std::string(e.what()).find("bad.cif:19: non-numeric x coordinate '17.0x7'") != std::string::npos);
}

TEST_CASE("read_molecule: gzipped PDB") {
  const std::string path = (scratch().dir / "small.pdb.gz").string();
  const std::string text = pdb_atom("ATOM", 1, " CA", ' ', "ALA", "A", 1, "1.000", "2.000", "3.000", "C") +
                           pdb_atom("ATOM", 2, " N", ' ', "ALA", "A", 1, "2.000", "2.000", "3.000", "N");
  gzFile f = gzopen(path.c_str(), "wb");
  REQUIRE(f != nullptr);
  gzwrite(f, text.data(), static_cast<unsigned>(text.size()));
  gzclose(f);
  const Molecule m = read_molecule(path);
  REQUIRE(m.atoms.size() == 2);
  CHECK(m.atoms[1].element == "N");
  CHECK(m.atoms[1].line == 2);
}

TEST_CASE("read_molecule: first model, first alternate location, fallback radius notes") {
  std::string text = "HEADER    TEST\nMODEL        1\n";
  text += pdb_atom("ATOM", 1, " N", ' ', "SER", "A", 5, "0.000", "0.000", "0.000", "N");     // line 3
  text += pdb_atom("ATOM", 2, " CA", 'A', "SER", "A", 5, "1.000", "0.000", "0.000", "C");    // kept
  text += pdb_atom("ATOM", 3, " CA", 'B', "SER", "A", 5, "1.100", "0.000", "0.000", "C");    // line 5 skipped
  text += pdb_atom("ATOM", 4, " CB", 'A', "SER", "A", 6, "2.000", "0.000", "0.000", "C");    // kept
  text += pdb_atom("ATOM", 5, " CB", 'B', "THR", "A", 6, "2.100", "0.000", "0.000", "C");    // alt residue
  text += pdb_atom("ATOM", 6, " OG1", 'B', "THR", "A", 6, "2.200", "0.000", "0.000", "O");   // alt residue
  text += pdb_atom("HETATM", 7, "FE", ' ', "HEM", "A", 7, "3.000", "0.000", "0.000", "FE");  // line 9
  text += "ENDMDL\nMODEL        2\n";
  text += pdb_atom("ATOM", 1, " N", ' ', "SER", "A", 5, "9.000", "0.000", "0.000", "N");
  text += "ENDMDL\nEND\n";
  const std::string path = scratch().write("altloc.pdb", text);
  const Molecule m = read_molecule(path);
  REQUIRE(m.atoms.size() == 4);
  CHECK(m.atoms[0].line == 3);
  CHECK(m.atoms[1].centre.x() == 1.0);
  CHECK(m.atoms[2].centre.x() == 2.0);
  CHECK(m.atoms[3].element == "Fe");
  CHECK(m.atoms[3].radius == skinmesh::skin::kFallbackRadius);
  CHECK(m.atoms[3].line == 9);
  REQUIRE(m.notes.size() == 4);
  CHECK(m.notes[0].rfind(path + ":5: alternate location B", 0) == 0);
  CHECK(m.notes[1].rfind(path + ":7: alternate location B", 0) == 0);
  CHECK(m.notes[2].rfind(path + ":8: alternate location B", 0) == 0);
  CHECK(m.notes[3].rfind(path + ":9: no Bondi radius for element Fe", 0) == 0);
}

TEST_CASE("read_molecule: atoms with equal coordinates, name and altloc get their own lines in file order") {
  // gemmi returns atoms regrouped by chain; the reader finds each one's line
  // by (x, y, z, name, altloc), and equal keys must be served in file order.
  // Chain B's atoms come between chain A's, so gemmi's order is not the file's.
  std::string text = "HEADER    TEST\n";
  text += pdb_atom("ATOM", 1, " CA", ' ', "GLY", "A", 1, "1.000", "2.000", "3.000", "C");  // line 2
  text += pdb_atom("ATOM", 2, " CA", ' ', "GLY", "B", 1, "1.000", "2.000", "3.000", "C");  // line 3
  text += pdb_atom("ATOM", 3, " H", ' ', "GLY", "B", 1, "1.000", "2.000", "3.000", "H");   // line 4
  text += pdb_atom("ATOM", 4, " CA", ' ', "GLY", "A", 2, "1.000", "2.000", "3.000", "C");  // line 5
  text += pdb_atom("ATOM", 5, " H", ' ', "GLY", "A", 2, "1.000", "2.000", "3.000", "H");   // line 6
  text += "END\n";
  const std::string path = scratch().write("ties.pdb", text);
  const Molecule m = read_molecule(path);
  REQUIRE(m.atoms.size() == 5);
  std::vector<int> lines, chain_a, chain_b;
  for (const auto& a : m.atoms) {
    lines.push_back(a.line);
    (a.chain == "A" ? chain_a : chain_b).push_back(a.line);
  }
  // Every atom has a line of its own, and each chain's keep file order.
  std::sort(lines.begin(), lines.end());
  CHECK(lines == std::vector<int>{2, 3, 4, 5, 6});
  CHECK(chain_a == std::vector<int>{2, 5, 6});
  CHECK(chain_b == std::vector<int>{3, 4});
  // Without hydrogens: each one is named at its own line.
  ReadOptions no_h;
  no_h.keep_hydrogens = false;
  const Molecule heavy = read_molecule(path, no_h);
  REQUIRE(heavy.atoms.size() == 3);
  REQUIRE(heavy.notes.size() == 2);
  std::vector<std::string> notes = heavy.notes;
  std::sort(notes.begin(), notes.end());
  CHECK(notes[0].rfind(path + ":4: hydrogen", 0) == 0);
  CHECK(notes[1].rfind(path + ":6: hydrogen", 0) == 0);
}

TEST_CASE("read_molecule: bad inputs name the file and the line") {
  SUBCASE("missing file") {
    const std::string path = (scratch().dir / "does_not_exist.pdb").string();
    const InputError e = error_of(path);
    CHECK(e.file() == path);
    CHECK(std::string(e.what()).find("cannot open file") != std::string::npos);
  }
  SUBCASE("unknown extension") {
    const std::string path = scratch().write("atoms.txt", "1 2 3 4\n");
    const InputError e = error_of(path);
    CHECK(std::string(e.what()).find("atoms.txt: unknown format (expected .pdb, .cif, .pqr, .xyzr or .xyzrn)") !=
          std::string::npos);
    // ... unless the format is given
    ReadOptions opt;
    opt.format = ReadOptions::Format::Xyzr;
    CHECK(read_molecule(path, opt).atoms.size() == 1);
  }
  SUBCASE("empty files") {
    for (const char* name : {"empty.pdb", "empty.pqr", "empty.xyzr", "empty.cif"}) {
      CAPTURE(name);
      const InputError e = error_of(scratch().write(name, name == std::string("empty.cif") ? "data_x\n" : ""));
      CHECK(std::string(e.what()).find(std::string(name) + ": no atoms found") != std::string::npos);
    }
  }
  SUBCASE("only waters") {
    const InputError e = error_of(
        scratch().write("water.pdb", pdb_atom("HETATM", 1, " O", ' ', "HOH", "A", 1, "1.0", "2.0", "3.0", "O")));
    CHECK(std::string(e.what()).find("no atoms found (1 skipped") != std::string::npos);
  }
  SUBCASE("PDB non-numeric coordinate (gemmi alone would read 0)") {
    const std::string text = "REMARK   1\n" +
                             pdb_atom("ATOM", 1, " CA", ' ', "ALA", "A", 1, "1.000", "2.000", "3.000", "C") +
                             pdb_atom("ATOM", 2, " CB", ' ', "ALA", "A", 1, "1.000", "abc", "3.000", "C");
    const InputError e = error_of(scratch().write("garbage.pdb", text));
    CHECK(e.line() == 3);
    CHECK(std::string(e.what()).find("garbage.pdb:3: non-numeric y coordinate 'abc'") != std::string::npos);
  }
  SUBCASE("PDB number followed by garbage (gemmi alone would read 12.1)") {
    const InputError e = error_of(scratch().write(
        "trailing.pdb", pdb_atom("ATOM", 1, " CA", ' ', "ALA", "A", 1, "12.1x4", "2.000", "3.000", "C")));
    CHECK(std::string(e.what()).find("trailing.pdb:1: non-numeric x coordinate '12.1x4'") != std::string::npos);
  }
  SUBCASE("PDB blank coordinate") {
    const InputError e =
        error_of(scratch().write("blank.pdb", pdb_atom("ATOM", 1, " CA", ' ', "ALA", "A", 1, "1.0", "2.0", "", "C")));
    CHECK(std::string(e.what()).find("blank.pdb:1: non-numeric z coordinate ''") != std::string::npos);
  }
  SUBCASE("PDB nan and inf") {
    const InputError e = error_of(
        scratch().write("nan.pdb", pdb_atom("ATOM", 1, " CA", ' ', "ALA", "A", 1, "1.0", "2.0", "3.0", "C") +
                                       pdb_atom("ATOM", 2, " CB", ' ', "ALA", "A", 1, "1.0", "2.0", "nan", "C")));
    CHECK(std::string(e.what()).find("nan.pdb:2: non-finite z coordinate 'nan'") != std::string::npos);
    const InputError f = error_of(
        scratch().write("inf.pdb", pdb_atom("ATOM", 1, " CA", ' ', "ALA", "A", 1, "-1e999", "2.0", "3.0", "C")));
    CHECK(std::string(f.what()).find("inf.pdb:1: non-finite x coordinate '-1e999'") != std::string::npos);
  }
  SUBCASE("PDB record too short for coordinates") {
    const InputError e = error_of(scratch().write("short.pdb", "ATOM      1  CA  ALA A   1       1.000   2.000\n"));
    CHECK(e.line() == 1);
    CHECK(std::string(e.what()).find("short.pdb:1: ATOM/HETATM record too short") != std::string::npos);
  }
  SUBCASE("PDB unknown element") {
    const InputError e = error_of(
        scratch().write("elem.pdb", pdb_atom("ATOM", 1, " CA", ' ', "ALA", "A", 1, "1.0", "2.0", "3.0", "C") +
                                        pdb_atom("HETATM", 2, "QQ", ' ', "UNK", "A", 2, "1.0", "2.0", "4.0", "QQ")));
    CHECK(std::string(e.what()).find("elem.pdb:2: unknown element") != std::string::npos);
  }
  SUBCASE("PQR: chain column optional, fields by whitespace") {
    const std::string text =
        "REMARK PQR\n"
        "ATOM      1  N   ALA     1      1.000  2.000  3.000 -0.3000 1.8240\n"
        "ATOM 2 CA ALA B 17 -1.5 2.25 3 0.1 1.9080\n"
        "HETATM 3 NA NA 18 10 10 10 1.0 1.8680\n";
    const Molecule m = read_molecule(scratch().write("ok.pqr", text));
    REQUIRE(m.atoms.size() == 3);
    CHECK(m.atoms[0].radius == 1.824);
    CHECK(m.atoms[0].chain.empty());
    CHECK(m.atoms[1].centre == skinmesh::Vec3(-1.5, 2.25, 3.0));
    CHECK(m.atoms[1].chain == "B");
    CHECK(m.atoms[1].residue_number == 17);
    CHECK(m.atoms[1].element == "C");
    CHECK(m.atoms[2].element == "Na");
    CHECK(m.atoms[2].line == 4);
  }
  SUBCASE("PQR hydrogen with radius 0 is skipped with a note") {
    const std::string text =
        "ATOM      1  N   ALA     1      1.000  2.000  3.000 -0.3000 1.8240\n"
        "ATOM      2  HA  ALA     1      1.500  2.000  3.000  0.1000 0.0000\n";
    const std::string path = scratch().write("h0.pqr", text);
    const Molecule m = read_molecule(path);
    CHECK(m.atoms.size() == 1);
    REQUIRE(m.notes.size() == 1);
    CHECK(m.notes[0].rfind(path + ":2: hydrogen atom HA of ALA 1 has radius 0; skipped", 0) == 0);
  }
  SUBCASE("PQR radius 0 on a carbon") {
    const std::string text =
        "ATOM      1  N   ALA     1      1.000  2.000  3.000 -0.3000 1.8240\n"
        "ATOM      2  CA  ALA     1      1.500  2.000  3.000  0.1000 0.0000\n";
    const InputError e = error_of(scratch().write("c0.pqr", text));
    CHECK(e.line() == 2);
    CHECK(std::string(e.what()).find("c0.pqr:2: non-positive radius '0.0000'") != std::string::npos);
  }
  SUBCASE("PQR negative radius on a hydrogen") {
    const InputError e = error_of(scratch().write("hneg.pqr", "ATOM 1 H ALA 1 1.0 2.0 3.0 0.1 -1.0\n"));
    CHECK(std::string(e.what()).find("hneg.pqr:1: non-positive radius '-1.0'") != std::string::npos);
  }
  SUBCASE("PQR non-numeric and non-finite fields") {
    const InputError e = error_of(scratch().write("x.pqr", "ATOM 1 CA ALA 1 abc 2.0 3.0 0.1 1.9\n"));
    CHECK(std::string(e.what()).find("x.pqr:1: non-numeric x coordinate 'abc'") != std::string::npos);
    const InputError f = error_of(scratch().write("r.pqr", "\nATOM 1 CA ALA 1 1.0 2.0 3.0 0.1 nan\n"));
    CHECK(std::string(f.what()).find("r.pqr:2: non-finite radius 'nan'") != std::string::npos);
    const InputError g = error_of(scratch().write("few.pqr", "ATOM 1 CA ALA 1.0 2.0 3.0 0.1 1.9\n"));
    CHECK(std::string(g.what()).find("few.pqr:1: PQR record has 9 fields") != std::string::npos);
  }
  SUBCASE("XYZR: comments, blank lines, line numbers") {
    const std::string text = "# MSMS input\n\n1.0 2.0 3.0 1.5\n  -1 -2 -3 2.0   # an ion\n";
    const Molecule m = read_molecule(scratch().write("ok.xyzr", text));
    REQUIRE(m.atoms.size() == 2);
    CHECK(m.atoms[0].line == 3);
    CHECK(m.atoms[1].line == 4);
    CHECK(m.atoms[1].centre == skinmesh::Vec3(-1, -2, -3));
    CHECK(m.atoms[1].radius == 2.0);
    CHECK(m.atoms[1].element.empty());
    CHECK(m.atoms[1].serial == 2);
  }
  SUBCASE("XYZR radius 0, non-numeric, nan, too few fields") {
    const InputError e = error_of(scratch().write("r0.xyzr", "1 2 3 1.5\n1 2 3 0\n"));
    CHECK(e.line() == 2);
    CHECK(std::string(e.what()).find("r0.xyzr:2: non-positive radius '0'") != std::string::npos);
    const InputError f = error_of(scratch().write("abc.xyzr", "1 abc 3 1.5\n"));
    CHECK(std::string(f.what()).find("abc.xyzr:1: non-numeric y coordinate 'abc'") != std::string::npos);
    const InputError g = error_of(scratch().write("nan.xyzr", "# c\nnan 2 3 1.5\n"));
    CHECK(std::string(g.what()).find("nan.xyzr:2: non-finite x coordinate 'nan'") != std::string::npos);
    const InputError h = error_of(scratch().write("three.xyzr", "1 2 3\n"));
    CHECK(std::string(h.what()).find("three.xyzr:1: expected 'x y z r'") != std::string::npos);
  }
}

TEST_CASE("hostile input: coordinates and radii outside the supported range are input errors with their line") {
  // Issue #7: a coordinate of 1e300 once reached the regular triangulation and
  // ended in an assertion of orient3d.
  const InputError x = error_of(scratch().write("far.xyzr", "0 0 0 1.5\n1e300 0 0 1.5\n"));
  CHECK(x.line() == 2);
  CHECK(x.problem().find("x coordinate") != std::string::npos);
  CHECK(x.problem().find("outside the supported range") != std::string::npos);
  const InputError r = error_of(scratch().write("huge_radius.xyzr", "0 0 0 1e300\n"));
  CHECK(r.line() == 1);
  CHECK(r.problem().find("radius") != std::string::npos);
  const std::string pdb = pdb_atom("ATOM", 1, "CA", ' ', "ALA", "A", 1, "0.000", "1e300", "0.000", "C") +
                          pdb_atom("ATOM", 2, "CB", ' ', "ALA", "A", 1, "1.000", "0.000", "0.000", "C");
  const InputError p = error_of(scratch().write("far.pdb", pdb));
  CHECK(p.line() == 1);
  CHECK(p.problem().find("y coordinate") != std::string::npos);
  // The edge of the range is accepted.
  const Molecule ok = read_molecule(scratch().write("edge.xyzr", "1e7 -1e7 0 1.5\n"));
  CHECK(ok.atoms.size() == 1);
}

TEST_CASE("read_molecule_from_string: the reader of read_molecule() on text in memory") {
  // The same atoms, notes and source as the file read.
  const std::string path = data_file("crambin_1crn.pdb");
  std::ifstream in(path, std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const Molecule from_file = read_molecule(path);
  const Molecule from_text = read_molecule_from_string(text, path);
  CHECK(from_text.source == path);
  REQUIRE(from_text.atoms.size() == from_file.atoms.size());
  for (std::size_t i = 0; i < from_text.atoms.size(); ++i) {
    CHECK(from_text.atoms[i].centre == from_file.atoms[i].centre);
    CHECK(from_text.atoms[i].radius == from_file.atoms[i].radius);
    CHECK(from_text.atoms[i].line == from_file.atoms[i].line);
  }
  CHECK(from_text.notes == from_file.notes);
  // The name chooses the format unless the options do, and names the errors.
  CHECK(read_molecule_from_string("1 2 3 1.5\n", "memory.xyzr").atoms.size() == 1);
  ReadOptions opt;
  opt.format = ReadOptions::Format::Pqr;
  CHECK(read_molecule_from_string("ATOM 1 CA ALA 1 1.0 2.0 3.0 0.1 1.9\n", "memory", opt).atoms.size() == 1);
  const InputError e = string_error_of("1 2 3\n", "memory.xyzr");
  CHECK(e.file() == "memory.xyzr");
  CHECK(e.line() == 1);
  CHECK(std::string(e.what()).find("memory.xyzr:1: expected 'x y z r'") != std::string::npos);
  CHECK(std::string(string_error_of("1 2 3 1.5\n", "memory.txt").what()).find("unknown format") != std::string::npos);
}

// Inputs found by the libFuzzer targets of tests/fuzz (make fuzz), each of which
// once crashed a sanitizer build or let a wrong value through.
TEST_CASE(".xyzrn: x y z r [n [name]], the name kept and MaSIF's parts read from it") {
  const Molecule m = skinmesh::skin::read_molecule_from_string(
      "17.047 14.099 3.625 1.55 1 A_1_x_THR_N_Green\n"
      "# a comment\n"
      "15.685 12.755 5.133 1.70 1 B_-12_A_ALA_C\n"
      "1 2 3 1.5\n"
      "4 5 6 1.5 1\n"
      "7 8 9 1.5 1 not_masif\n",
      "t.xyzrn");
  REQUIRE(m.atoms.size() == 5);
  CHECK(m.atoms[0].msms_name == "A_1_x_THR_N_Green");
  CHECK(m.atoms[0].chain == "A");
  CHECK(m.atoms[0].residue_number == 1);
  CHECK(m.atoms[0].insertion_code == ' ');
  CHECK(m.atoms[0].residue == "THR");
  CHECK(m.atoms[0].name == "N");
  CHECK(m.atoms[0].radius == 1.55);
  CHECK(m.atoms[0].line == 1);
  CHECK(m.atoms[1].residue_number == -12);
  CHECK(m.atoms[1].insertion_code == 'A');
  CHECK(m.atoms[1].name == "C");
  CHECK(m.atoms[2].msms_name.empty());
  CHECK(m.atoms[3].msms_name.empty());
  CHECK(m.atoms[4].msms_name == "not_masif");
  CHECK(m.atoms[4].name.empty());  // not MaSIF's form: kept whole, not split
  // The same lines as .xyzr: the names ignored.
  const Molecule r = skinmesh::skin::read_molecule_from_string("1 2 3 1.5 1 A_1_x_THR_N\n", "t.xyzr");
  REQUIRE(r.atoms.size() == 1);
  CHECK(r.atoms[0].msms_name.empty());
  CHECK_THROWS_AS(skinmesh::skin::read_molecule_from_string("1 2 3\n", "t.xyzrn"), InputError);
}

TEST_CASE("real-file shapes other tools read: element text, guessed elements, PyMOL mmCIF, hybrid-36") {
  // tests/data/readers: one small file per class of file that used to be
  // refused (papers/skin/molecule_io.md, "Files other tools read"). Each
  // holds crambin's first two residues (14 atoms: N C C O C O C ×2 ...).
  const std::string dir = std::string(SKINMESH_TEST_DATA) + "/readers/";
  const Molecule crambin = read_molecule(data_file("crambin_1crn.pdb"));
  std::vector<std::string> first14;
  for (std::size_t i = 0; i < 14; ++i) first14.push_back(crambin.atoms[i].element);
  auto elements = [](const Molecule& m) {
    std::vector<std::string> e;
    for (const auto& a : m.atoms) e.push_back(a.element);
    return e;
  };
  auto one_note_containing = [](const Molecule& m, const std::string& text) {
    return std::count_if(m.notes.begin(), m.notes.end(),
                         [&](const std::string& n) { return n.find(text) != std::string::npos; }) == 1;
  };
  SUBCASE("columns 77-78 hold segment or serial text: elements from the names, one note") {
    for (const char* name : {"element_columns_hold_text.pdb", "element_columns_hold_serials.pdb"}) {
      CAPTURE(name);
      const Molecule m = read_molecule(dir + name);
      CHECK(elements(m) == first14);
      CHECK(m.notes.size() == 1);
      CHECK(one_note_containing(m, "elements guessed from atom names"));
      for (std::size_t i = 0; i < m.atoms.size(); ++i) CHECK(m.atoms[i].radius == crambin.atoms[i].radius);
    }
    CHECK(one_note_containing(read_molecule(dir + "element_columns_hold_text.pdb"),
                              "text that is no element symbol in columns 77-78 (first: line 2"));
  }
  SUBCASE("no element columns: the PDB convention, and the first letter where two spell no element") {
    const Molecule m = read_molecule(dir + "element_from_atom_names.pdb");
    std::vector<std::string> want{"C", "C", "O", "O"};  // ACE: CH3 (column 13), C, O, OLIN (column 13)
    want.insert(want.end(), first14.begin(), first14.end());
    want.push_back("Zn");  // a two-letter name from column 13 that is an element
    CHECK(elements(m) == want);
    CHECK(m.notes.size() == 1);
    CHECK(one_note_containing(m, "19 atoms have no element column"));
  }
  SUBCASE("hybrid-36 serials and residue numbers") {
    const Molecule m = read_molecule(dir + "hybrid36_serials.pdb");
    REQUIRE(m.atoms.size() == 14);
    CHECK(elements(m) == first14);
    CHECK(m.notes.empty());
    CHECK(m.atoms[4].serial == 99999);
    CHECK(m.atoms[5].serial == 100000);  // "A0000"
    CHECK(m.atoms[13].serial == 100008);
    CHECK(m.atoms[0].residue_number == 9999);
    CHECK(m.atoms[13].residue_number == 10000);  // "A000"
  }
  SUBCASE("a minimal mmCIF as PyMOL writes it") {
    const Molecule m = read_molecule(dir + "pymol_minimal.cif");
    REQUIRE(m.atoms.size() == 14);
    CHECK(elements(m) == first14);
    for (std::size_t i = 0; i < m.atoms.size(); ++i) {
      CHECK(m.atoms[i].centre == crambin.atoms[i].centre);
      CHECK(m.atoms[i].residue_number == crambin.atoms[i].residue_number);
      CHECK(m.atoms[i].chain == "A");
    }
    CHECK(one_note_containing(m, "_atom_site has no auth_seq_id"));
  }
}

TEST_CASE("models: model_numbers lists them, ReadOptions::model reads one, a missing one is refused") {
  // tests/data/readers/nmr_three_models.pdb: crambin's residues 1-5 as model 1,
  // moved 0.5 Å along x as model 2, rotated 20° about z as model 3.
  const std::string path = std::string(SKINMESH_TEST_DATA) + "/readers/nmr_three_models.pdb";
  CHECK(skinmesh::skin::model_numbers(path) == std::vector<int>{1, 2, 3});
  CHECK(skinmesh::skin::model_numbers(data_file("crambin_1crn.pdb")) == std::vector<int>{1});
  CHECK(skinmesh::skin::model_numbers(data_file("crambin_1crn.pqr")) == std::vector<int>{1});
  ReadOptions opt;
  const Molecule first = read_molecule(path);
  REQUIRE(first.atoms.size() == 35);
  opt.model = 1;
  const Molecule one = read_molecule(path, opt);
  opt.model = 2;
  const Molecule two = read_molecule(path, opt);
  opt.model = 3;
  const Molecule three = read_molecule(path, opt);
  REQUIRE(one.atoms.size() == 35);
  REQUIRE(two.atoms.size() == 35);
  REQUIRE(three.atoms.size() == 35);
  const double c = std::cos(20 * std::acos(-1.0) / 180), s = std::sin(20 * std::acos(-1.0) / 180);
  for (std::size_t i = 0; i < 35; ++i) {
    const auto& p = one.atoms[i].centre;
    CHECK(first.atoms[i].centre == p);
    CHECK(two.atoms[i].centre.x() == doctest::Approx(p.x() + 0.5).epsilon(1e-12));
    CHECK(two.atoms[i].centre.y() == p.y());
    CHECK(std::abs(three.atoms[i].centre.x() - (c * p.x() - s * p.y())) <= 5.0001e-4);  // three decimals
    CHECK(std::abs(three.atoms[i].centre.y() - (s * p.x() + c * p.y())) <= 5.0001e-4);
    CHECK(two.atoms[i].line == one.atoms[i].line + 38);  // the records of model 2, by their lines
    CHECK(two.atoms[i].name == one.atoms[i].name);
  }
  opt.model = 4;
  try {
    read_molecule(path, opt);
    FAIL("model 4 was read");
  } catch (const InputError& e) {
    CHECK(std::string(e.what()).find("no atoms in model 4 (the file's models: 1, 2, 3") != std::string::npos);
  }
  // A file without MODEL records holds model 1 only; PQR and XYZR have no other.
  opt.model = 1;
  CHECK(read_molecule(data_file("ligand_2zmm.pdb"), opt).atoms.size() ==
        read_molecule(data_file("ligand_2zmm.pdb")).atoms.size());
  opt.model = 2;
  CHECK_THROWS_AS(read_molecule(data_file("ligand_2zmm.pdb"), opt), InputError);
  CHECK_THROWS_AS(read_molecule(data_file("crambin_1crn.pqr"), opt), InputError);
}

TEST_CASE("assemblies: PDB REMARK 350 and mmCIF _pdbx_struct_assembly expand the model, the copies named A2") {
  // tests/data/readers/assembly_dimer.{pdb,cif}: crambin's residues 1-5 as
  // chain A; assembly 1 adds a copy rotated 180° about z and moved 30 Å along x,
  // assembly 2 is A alone.
  const std::string dir = std::string(SKINMESH_TEST_DATA) + "/readers/";
  for (const char* name : {"assembly_dimer.pdb", "assembly_dimer.cif"}) {
    CAPTURE(name);
    const Molecule plain = read_molecule(dir + name);
    REQUIRE(plain.atoms.size() == 35);
    // Ids assigned as strings: GCC 12 warns falsely (-Wrestrict) on literals here.
    const std::string ids[] = {"1", "2", "3"};
    ReadOptions opt;
    opt.assembly = ids[0];
    const Molecule dimer = read_molecule(dir + name, opt);
    REQUIRE(dimer.atoms.size() == 70);
    for (std::size_t i = 0; i < 35; ++i) {
      const auto& a = plain.atoms[i];
      CHECK(dimer.atoms[i].centre == a.centre);
      CHECK(dimer.atoms[i].chain == "A");
      const auto& b = dimer.atoms[35 + i];
      CHECK(b.centre.x() == doctest::Approx(30 - a.centre.x()).epsilon(1e-12));
      CHECK(b.centre.y() == doctest::Approx(-a.centre.y()).epsilon(1e-12));
      CHECK(b.centre.z() == a.centre.z());
      CHECK(b.chain == "A2");
      CHECK(b.name == a.name);
      CHECK(b.element == a.element);
      CHECK(b.radius == a.radius);
    }
    CHECK(std::count_if(dimer.notes.begin(), dimer.notes.end(), [](const std::string& n) {
            return n.find("assembly 1: 2 operators, 70 atoms") != std::string::npos;
          }) == 1);
    opt.assembly = ids[1];
    CHECK(read_molecule(dir + name, opt).atoms.size() == 35);
    opt.assembly = ids[2];
    try {
      read_molecule(dir + name, opt);
      FAIL("assembly 3 was read");
    } catch (const InputError& e) {
      CHECK(std::string(e.what()).find("no assembly 3 (the file lists: 1, 2)") != std::string::npos);
    }
  }
  ReadOptions opt;
  opt.assembly = "1";
  CHECK_THROWS_WITH_AS(read_molecule(data_file("ligand_2zmm.pdb"), opt), doctest::Contains("the file lists none"),
                       InputError);
  CHECK_THROWS_AS(read_molecule(data_file("crambin_1crn.pqr"), opt), InputError);
  // A bundled file whose assembly is the identity: the same atoms.
  CHECK(read_molecule(data_file("crambin_1crn.pdb"), opt).atoms.size() == 327);
}

TEST_CASE("models and assemblies together: the header's REMARK 350 expands model 2 (PDB), rows by number (mmCIF)") {
  // nmr_three_models.pdb with assembly_dimer.pdb's REMARK 350 block in its header.
  const std::string dir = std::string(SKINMESH_TEST_DATA) + "/readers/";
  std::ifstream nmr_file(dir + "nmr_three_models.pdb"), dimer_file(dir + "assembly_dimer.pdb");
  std::string nmr((std::istreambuf_iterator<char>(nmr_file)), {}), remarks, line;
  for (std::istringstream dimer(std::string((std::istreambuf_iterator<char>(dimer_file)), {}));
       std::getline(dimer, line);)
    if (line.rfind("REMARK 350", 0) == 0) remarks += line + "\n";
  nmr.insert(nmr.find("\nMODEL") + 1, remarks);
  ReadOptions opt;
  opt.model = 2;
  const Molecule two = read_molecule_from_string(nmr, "ensemble.pdb", opt);
  REQUIRE(two.atoms.size() == 35);
  const std::string id = "1";
  opt.assembly = id;
  const Molecule dimer = read_molecule_from_string(nmr, "ensemble.pdb", opt);
  REQUIRE(dimer.atoms.size() == 70);
  for (std::size_t i = 0; i < 35; ++i) {
    CHECK(dimer.atoms[i].centre == two.atoms[i].centre);  // model 2's atoms, then their copy
    CHECK(dimer.atoms[35 + i].centre.x() == doctest::Approx(30 - two.atoms[i].centre.x()).epsilon(1e-12));
  }
}

TEST_CASE("chains: ReadOptions::chains keeps those chains' atoms in file order; an absent chain is refused") {
  const Molecule all = read_molecule(data_file("hivprotease_xk263_1hvr.pdb"));
  CHECK(skinmesh::skin::chain_names(all) == std::vector<std::string>{"A", "B"});
  ReadOptions opt;
  opt.chains = {"B"};
  const Molecule b = read_molecule(data_file("hivprotease_xk263_1hvr.pdb"), opt);
  std::vector<skinmesh::skin::Atom> expected;
  for (const auto& a : all.atoms)
    if (a.chain == "B") expected.push_back(a);
  REQUIRE(b.atoms.size() == expected.size());
  REQUIRE(b.atoms.size() == 922);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    CHECK(b.atoms[i].centre == expected[i].centre);
    CHECK(b.atoms[i].line == expected[i].line);
  }
  opt.chains = {"B", "A"};
  CHECK(read_molecule(data_file("hivprotease_xk263_1hvr.pdb"), opt).atoms.size() == all.atoms.size());
  opt.chains = {"C"};
  CHECK_THROWS_WITH_AS(read_molecule(data_file("hivprotease_xk263_1hvr.pdb"), opt),
                       doctest::Contains("no atoms in chain 'C' (the chains read: A, B"), InputError);
  // After the assembly's expansion: the copy is chain A2.
  const std::string ids[] = {"1", "A2"};
  opt.assembly = ids[0];
  opt.chains = {ids[1]};
  const Molecule copy = read_molecule(std::string(SKINMESH_TEST_DATA) + "/readers/assembly_dimer.pdb", opt);
  const Molecule plain = read_molecule(std::string(SKINMESH_TEST_DATA) + "/readers/assembly_dimer.pdb");
  REQUIRE(copy.atoms.size() == plain.atoms.size());
  for (std::size_t i = 0; i < copy.atoms.size(); ++i)
    CHECK(copy.atoms[i].centre.x() == doctest::Approx(30 - plain.atoms[i].centre.x()).epsilon(1e-12));
}

TEST_CASE("fuzzing regressions: PDB") {
  SUBCASE("a LINK record of 74-77 columns is not read past its end") {
    // fuzz_pdb: heap-buffer-overflow in gemmi 0.5.7 pdb_impl::process_conn,
    // which reads the LINK distance (columns 74-78) from an exact-length copy of
    // the record. Records other than ATOM, HETATM, MODEL, ENDMDL, TER and END
    // no longer reach gemmi.
    const std::string found =
        "CtMAP\n"
        "LINK CCCCCCCCC1GZMCCCCCCCCCCCCCCCCCCCCCCCCCCCCCCC\010CCCCCCCCCCCCCCCCCCCCCC ";
    CHECK(std::string(string_error_of(found, "link.pdb").what()).find("no atoms found") != std::string::npos);
    // A zinc site whose LINK record ends in a blank at column 74.
    const std::string link = "LINK         SG  CYS A   1                 ZN    ZN A   2     1555   1555 \n";
    REQUIRE(link.size() == 75);
    const std::string text = pdb_atom("ATOM", 1, " SG", ' ', "CYS", "A", 1, "1.000", "2.000", "3.000", " S") +
                             pdb_atom("HETATM", 2, "ZN", ' ', " ZN", "A", 2, "3.000", "2.000", "3.000", "ZN") + link +
                             "SSBOND   1 CYS A    1    CYS A    1\nCISPEP   1 CYS A    1    ZN A    2\n";
    const Molecule m = read_molecule_from_string(text, "zinc.pdb");
    REQUIRE(m.atoms.size() == 2);
    CHECK(m.atoms[1].element == "Zn");
    CHECK(m.atoms[1].line == 2);
  }
  SUBCASE("gemmi reads the lines the pre-scan checked, no others") {
    // fuzz_pdb (after the fix above): heap-buffer-overflow again, on a LINK
    // record the pre-scan never saw. gemmi reads at most 120 columns of a line
    // and drops the rest up to a newline, a NUL or a byte >= 0x80, where it
    // starts its next line: mid-line for the pre-scan. gemmi now reads the
    // lines of the pre-scan (cut to 120 columns, NUL and CR made blanks).
    using namespace std::string_literals;
    const std::string found =
        ";;;.02APR;;3;;;;;;;;;;;;;;;;;;;;;;;;;;;;;;;;;;;;;;\017\000\000\000\000\000\000\000;;;;;;;;;;;;;;;;;;;;;;;;;;;;"
        ";;;;;;;;;;;;;+;;;;; 0;;;;;;;;;;;;0\351LINK ;;;;;;;;;;;T4P;;;;;;;;;;;;;;;;;;;;;APR;;;;;;;;; 1;;;;;;;;;;;;0\351LINK "s;
    CHECK(std::string(string_error_of(found, "resync.pdb").what()).find("no atoms found") != std::string::npos);
    // The same way, an atom record hidden after column 120 reached gemmi
    // unchecked: "nan" came back as NaN, "abc" as 0.
    const std::string atom = pdb_atom("ATOM", 2, " CB", ' ', "GLY", "A", 1, "1.0", "2.0", "3.0", "C");
    for (const char* hidden : {"nan", "abc"}) {
      CAPTURE(hidden);
      std::string record = pdb_atom("ATOM", 1, " CA", ' ', "GLY", "A", 1, hidden, "0.0", "0.0", "C");
      record.pop_back();  // its newline
      for (const std::string& separator : {"\351"s, "\000"s}) {
        const std::string text = "REMARK" + std::string(114, ' ') + "x" + separator + record + "\n" + atom;
        const Molecule m = read_molecule_from_string(text, "hidden.pdb");
        REQUIRE(m.atoms.size() == 1);
        CHECK(m.atoms[0].centre == skinmesh::Vec3(1.0, 2.0, 3.0));
        CHECK(m.atoms[0].line == 2);
      }
    }
  }
  SUBCASE("records the reader does not use do not reach gemmi") {
    // fuzz_pdb (after the fixes above): signed integer overflow (undefined
    // behaviour) in gemmi 0.5.7, which reads the DBREF2 numbers, columns 46-55
    // and 58-67, into an int without overflow check; a short DBREF2 record even
    // has them read from the previous, longer line. gemmi now gets only the
    // ATOM, HETATM, MODEL, ENDMDL, TER and END records.
    const std::string found =
        "ATOM      9 SE   MSE A  48       0.40999999999999999999\n"
        "DBREF1\n"
        "DBREF2";
    CHECK(string_error_of(found, "dbref.pdb").problem().find("outside the supported range") != std::string::npos);
    const std::string dbref2 =
        "DBREF1 1ABC A    1    10  UNP                  ABC_HUMAN\n"
        "DBREF2 1ABC A     P12345                     9999999999  9999999999\n";
    const Molecule m =
        read_molecule_from_string(dbref2 + "HELIX    1   1 GLY A    1  GLY A    1  1 99999999999\n" +
                                      pdb_atom("ATOM", 1, " CA", ' ', "GLY", "A", 1, "1.0", "2.0", "3.0", "C"),
                                  "dbref.pdb");
    REQUIRE(m.atoms.size() == 1);
    CHECK(m.atoms[0].line == 4);
  }
  SUBCASE("a later MODEL re-entering an empty first model is not read unchecked") {
    // gemmi puts the atoms of the second "MODEL 1" into its first model, which
    // the pre-scan had closed at the first ENDMDL: x = "nan" came back as NaN.
    // gemmi now sees the text up to the end of the first model only.
    const std::string text = "MODEL        1\nENDMDL\nMODEL        2\n" +
                             pdb_atom("ATOM", 1, " CA", ' ', "GLY", "A", 1, "1.0", "2.0", "3.0", "C") +
                             "ENDMDL\nMODEL        1\n" +
                             pdb_atom("ATOM", 2, " CA", ' ', "GLY", "A", 1, "nan", "0.0", "0.0", "C") + "ENDMDL\n";
    const InputError e = string_error_of(text, "reenter.pdb");
    CHECK(std::string(e.what()).find("no atoms found") != std::string::npos);
    // The first model with atoms is read as before; later models are not looked at.
    const std::string two = "MODEL        1\n" +
                            pdb_atom("ATOM", 1, " CA", ' ', "GLY", "A", 1, "1.0", "2.0", "3.0", "C") +
                            "ENDMDL\nMODEL        2\n" +
                            pdb_atom("ATOM", 1, " CA", ' ', "GLY", "A", 1, "nan", "2.0", "3.0", "C") + "ENDMDL\n";
    const Molecule m = read_molecule_from_string(two, "two_models.pdb");
    REQUIRE(m.atoms.size() == 1);
    CHECK(m.atoms[0].centre == skinmesh::Vec3(1.0, 2.0, 3.0));
    CHECK(m.atoms[0].line == 2);
  }
}

TEST_CASE("fuzzing regressions: mmCIF integers beyond int") {
  // fuzz_cif: signed integer overflow (undefined behaviour) in gemmi 0.5.7
  // string_to_int(), which reads _atom_site.id and every integer of the other
  // categories without overflow checks. gemmi now sees the _atom_site items
  // only, with integers beyond int read as absent (0).
  const std::string loop =
      "loop_\n"
      "_atom_site.group_PDB\n"
      "_atom_site.id\n"
      "_atom_site.type_symbol\n"
      "_atom_site.label_atom_id\n"
      "_atom_site.label_alt_id\n"
      "_atom_site.label_comp_id\n"
      "_atom_site.label_asym_id\n"
      "_atom_site.label_entity_id\n"
      "_atom_site.label_seq_id\n"
      "_atom_site.pdbx_PDB_ins_code\n"
      "_atom_site.Cartn_x\n"
      "_atom_site.Cartn_y\n"
      "_atom_site.Cartn_z\n"
      "_atom_site.occupancy\n"
      "_atom_site.B_iso_or_equiv\n"
      "_atom_site.pdbx_formal_charge\n"
      "_atom_site.auth_seq_id\n"
      "_atom_site.auth_comp_id\n"
      "_atom_site.auth_asym_id\n"
      "_atom_site.auth_atom_id\n"
      "_atom_site.pdbx_PDB_model_num\n";
  SUBCASE("the input found: _atom_site.id 318446744073709551616") {
    const std::string found =
        "data_1CRN\n" + loop +
        "ATOM 318446744073709551616 C C . THR A 1 1 ? 15.685 12.755 5.133 1.00 9.19 ? 1 THR A C 1\n";
    const Molecule m = read_molecule_from_string(found, "serial.cif");
    REQUIRE(m.atoms.size() == 1);
    CHECK(m.atoms[0].serial == 0);
    CHECK(m.atoms[0].centre == skinmesh::Vec3(15.685, 12.755, 5.133));
    CHECK(m.atoms[0].line == 24);
  }
  SUBCASE("residue numbers, charges; other categories") {
    const std::string text = "data_x\n" + loop +
                             "ATOM 1 C CA . GLY A 1 99999999999 ? 1.0 2.0 3.0 1 0 -2147483649 99999999999 GLY A CA 1\n"
                             "ATOM 2 C C . GLY A 1 1 ? 4.0 5.0 6.0 1 0 ? 7 GLY A C 1\n"
                             "loop_\n_entity.id\n_entity.type\n1 polymer\n"
                             "loop_\n_entity_poly_seq.entity_id\n_entity_poly_seq.num\n_entity_poly_seq.mon_id\n"
                             "1 99999999999 GLY\n";
    const Molecule m = read_molecule_from_string(text, "numbers.cif");
    REQUIRE(m.atoms.size() == 2);
    CHECK(m.atoms[0].residue_number == 0);
    CHECK(m.atoms[1].residue_number == 7);
    CHECK(m.atoms[1].serial == 2);
  }
}

}  // TEST_SUITE("skin")

// skin/element_radii.cpp: Bondi (1964) van der Waals radii and element symbols.
#include "skin/element_radii.h"

#include <array>
#include <cctype>

namespace skinmesh::skin {

namespace {

// Element Radii Tables

struct BondiEntry {
  std::string_view symbol;
  double radius;  // Å
};

// A. Bondi, J. Phys. Chem. 68 (1964) 441, Table I (values as usually quoted).
constexpr std::array<BondiEntry, 38> kBondi = {{
    {"H", 1.20},  {"He", 1.40}, {"Li", 1.82}, {"C", 1.70},  {"N", 1.55},  {"O", 1.52},  {"F", 1.47},  {"Ne", 1.54},
    {"Na", 2.27}, {"Mg", 1.73}, {"Si", 2.10}, {"P", 1.80},  {"S", 1.80},  {"Cl", 1.75}, {"Ar", 1.88}, {"K", 2.75},
    {"Ni", 1.63}, {"Cu", 1.40}, {"Zn", 1.39}, {"Ga", 1.87}, {"As", 1.85}, {"Se", 1.90}, {"Br", 1.85}, {"Kr", 2.02},
    {"Pd", 1.63}, {"Ag", 1.72}, {"Cd", 1.58}, {"In", 1.93}, {"Sn", 2.17}, {"Te", 2.06}, {"I", 1.98},  {"Xe", 2.16},
    {"Pt", 1.72}, {"Au", 1.66}, {"Hg", 1.55}, {"Tl", 1.96}, {"Pb", 2.02}, {"U", 1.86},
}};

// The periodic table by atomic number (index 0 unused), then deuterium.
constexpr std::array<std::string_view, 120> kSymbols = {
    "",   "H",  "He", "Li", "Be", "B",  "C",  "N",  "O",  "F",  "Ne", "Na", "Mg", "Al", "Si", "P",  "S",  "Cl",
    "Ar", "K",  "Ca", "Sc", "Ti", "V",  "Cr", "Mn", "Fe", "Co", "Ni", "Cu", "Zn", "Ga", "Ge", "As", "Se", "Br",
    "Kr", "Rb", "Sr", "Y",  "Zr", "Nb", "Mo", "Tc", "Ru", "Rh", "Pd", "Ag", "Cd", "In", "Sn", "Sb", "Te", "I",
    "Xe", "Cs", "Ba", "La", "Ce", "Pr", "Nd", "Pm", "Sm", "Eu", "Gd", "Tb", "Dy", "Ho", "Er", "Tm", "Yb", "Lu",
    "Hf", "Ta", "W",  "Re", "Os", "Ir", "Pt", "Au", "Hg", "Tl", "Pb", "Bi", "Po", "At", "Rn", "Fr", "Ra", "Ac",
    "Th", "Pa", "U",  "Np", "Pu", "Am", "Cm", "Bk", "Cf", "Es", "Fm", "Md", "No", "Lr", "Rf", "Db", "Sg", "Bh",
    "Hs", "Mt", "Ds", "Rg", "Cn", "Nh", "Fl", "Mc", "Lv", "Ts", "Og", "D",
};
static_assert(kSymbols[118] == "Og" && kSymbols[119] == "D", "periodic table misnumbered");

/// An element symbol in standard capitalisation, held in place (symbols have one
/// or two letters, so no allocation).
struct Symbol {
  std::array<char, 2> letters{};
  std::size_t size = 0;
  std::string_view view() const { return {letters.data(), size}; }
};

/// `s` without surrounding blanks, first letter upper case, second lower case;
/// size 0 if that is not one or two characters.
Symbol capitalised(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  Symbol out;
  if (s.empty() || s.size() > 2) return out;
  out.size = s.size();
  out.letters[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(s[0])));
  if (s.size() == 2) out.letters[1] = static_cast<char>(std::tolower(static_cast<unsigned char>(s[1])));
  return out;
}

}  // namespace

// Element Radii Function Definitions

std::optional<double> bondi_radius(std::string_view symbol) {
  const Symbol s = capitalised(symbol);
  // deuterium: same electron shell as hydrogen
  const std::string_view key = s.view() == "D" ? std::string_view("H") : s.view();
  for (const BondiEntry& e : kBondi)
    if (e.symbol == key) return e.radius;
  return std::nullopt;
}

VanDerWaalsRadius van_der_waals_radius(std::string_view symbol) {
  if (std::optional<double> r = bondi_radius(symbol)) return {*r, true};
  return {kFallbackRadius, false};
}

std::string canonical_element_symbol(std::string_view symbol) {
  const Symbol s = capitalised(symbol);
  if (s.size == 0) return {};
  for (std::size_t z = 1; z < kSymbols.size(); ++z)
    if (kSymbols[z] == s.view()) return std::string(s.view());
  return {};
}

}  // namespace skinmesh::skin

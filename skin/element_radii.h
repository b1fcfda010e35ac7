// skin/element_radii.h: van der Waals radii by element symbol, the ball radii
// given to atoms read from PDB/mmCIF files (PQR and XYZR files carry their own).
// Source: A. Bondi, "van der Waals Volumes and Radii", J. Phys. Chem. 68 (1964) 441.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace skinmesh::skin {

// Element Radii Constants

/// Radius (Å) used for an element that Bondi (1964) does not list, in practice the
/// metal ions of proteins (Fe, Ca, Mn, Co, Mo, ...). It is a round value of the
/// order of Bondi's radii for the neighbouring elements he does list (1.39-2.75 Å),
/// not a measured van der Waals radius; readers record a note for every atom that
/// gets it (skin/molecule_io).
inline constexpr double kFallbackRadius = 2.0;

// Element Radii Public Functions

/// Bondi's van der Waals radius (Å) of `symbol`, or nullopt if Bondi does not
/// list the element (or `symbol` is not an element). `symbol` is matched without
/// regard to case or surrounding blanks ("CL", " Cl", "cl" all mean chlorine).
/// Deuterium "D" gets the hydrogen radius. The table holds the 38 elements of
/// Bondi's Table I as usually quoted: H 1.20, He 1.40, Li 1.82, C 1.70, N 1.55,
/// O 1.52, F 1.47, Ne 1.54, Na 2.27, Mg 1.73, Si 2.10, P 1.80, S 1.80, Cl 1.75,
/// Ar 1.88, K 2.75, Ni 1.63, Cu 1.40, Zn 1.39, Ga 1.87, As 1.85, Se 1.90, Br 1.85,
/// Kr 2.02, Pd 1.63, Ag 1.72, Cd 1.58, In 1.93, Sn 2.17, Te 2.06, I 1.98, Xe 2.16,
/// Pt 1.72, Au 1.66, Hg 1.55, Tl 1.96, Pb 2.02, U 1.86 (some compilations quote
/// Pt 1.75). Throws nothing.
std::optional<double> bondi_radius(std::string_view symbol);

/// A radius chosen for an element: Bondi's value, or kFallbackRadius when Bondi
/// does not list the element (`from_bondi` false).
struct VanDerWaalsRadius {
  double radius = kFallbackRadius;  ///< Å
  bool from_bondi = false;
};

/// bondi_radius(symbol) if Bondi lists it, else {kFallbackRadius, false}. The
/// caller decides whether `symbol` is a real element (canonical_element_symbol)
/// and records the fallback. Throws nothing.
VanDerWaalsRadius van_der_waals_radius(std::string_view symbol);

/// `symbol` in standard capitalisation ("CL" -> "Cl", " fe" -> "Fe") if it names
/// one of the 118 elements or deuterium "D", else the empty string. Blanks around
/// the symbol are ignored. Throws nothing but std::bad_alloc.
std::string canonical_element_symbol(std::string_view symbol);

}  // namespace skinmesh::skin

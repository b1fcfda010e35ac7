// skin/singular_skin.cpp: require_non_singular().
#include "skin/singular_skin.h"

#include <cmath>
#include <sstream>

#include "core/errors.h"
#include "skin/mixed_cell_distance.h"
#include "skin/mixed_complex.h"

namespace skinmesh::skin {

void require_non_singular(const skin::SkinSurface& skin) {
  constexpr double kSingularScale = 1e-6;
  const skin::MixedComplex& mc = skin.mixed_complex();
  const double eps = kSingularScale * mc.length_scale();
  for (Index c = 0; c < mc.num_cells(); ++c) {
    // The cells' geometry is made for the test and not kept.
    if (mc.simplex(c).dim == 0 || mc.simplex(c).bounding) continue;
    const skin::MixedCell X = mc.cell_value(c);
    if (!(std::abs(X.focus_weight) <= 2 * eps * eps)) continue;
    if (!(cell_distance(mc, c, X.focus) <= eps)) continue;
    static const char* const kWhat[4] = {"", "touch", "meet at one point", "meet at one point"};
    std::ostringstream os;
    os.precision(2);
    os << "singular skin: the balls of atoms";
    for (int i = 0; i <= X.dim; ++i) os << (i ? (i == X.dim ? " and " : ", ") : " ") << '#' << X.vertices[i] + 1;
    os << " (input order) " << kWhat[X.dim] << ": the skin pinches there (radius "
       << std::sqrt(std::abs(X.focus_weight) / 2) << " Å < " << eps
       << " Å, 1e-6 of the molecule's size); move one of these atoms or change the probe radius by ~1e-4 Å";
    throw InputError("", 0, os.str());
  }
}

}  // namespace skinmesh::skin

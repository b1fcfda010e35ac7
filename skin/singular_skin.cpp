// skin/singular_skin.cpp: require_non_singular().
#include "skin/singular_skin.h"

#include <cmath>
#include <sstream>

#include "core/errors.h"
#include "core/parallel.h"
#include "skin/mixed_cell_distance.h"
#include "skin/mixed_complex.h"

namespace skinmesh::skin {

void require_non_singular(const skin::SkinSurface& skin, int threads) {
  constexpr double kSingularScale = 1e-6;
  constexpr std::size_t kGrain = 16384;  // [chosen] cells per block: a few ms
  const skin::MixedComplex& mc = skin.mixed_complex();
  const double eps = kSingularScale * mc.length_scale();
  // On the threads: parallel_for rethrows the lowest block's error, the first
  // singular cell's, as one loop finds it.
  parallel_for(mc.num_cells(), threads, kGrain, [&](std::size_t i) {
    const Index c = static_cast<Index>(i);
    // The cells' geometry is made for the test and not kept.
    if (mc.simplex(c).dim == 0 || mc.simplex(c).bounding) return;
    const skin::MixedCell X = mc.cell_value(c);
    if (!(std::abs(X.focus_weight) <= 2 * eps * eps)) return;
    if (!(cell_distance(mc, c, X.focus) <= eps)) return;
    static const char* const kWhat[4] = {"", "touch", "meet at one point", "meet at one point"};
    std::ostringstream os;
    os.precision(2);
    os << "singular skin: the balls of atoms";
    for (int i = 0; i <= X.dim; ++i) os << (i ? (i == X.dim ? " and " : ", ") : " ") << '#' << X.vertices[i] + 1;
    os << " (input order) " << kWhat[X.dim] << ": the skin pinches there (radius "
       << std::sqrt(std::abs(X.focus_weight) / 2) << " Å < " << eps
       << " Å, 1e-6 of the molecule's size); move one of these atoms or change the probe radius by ~1e-4 Å";
    throw InputError("", 0, os.str());
  });
}

}  // namespace skinmesh::skin

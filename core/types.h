// core/types.h: basic types shared by every module (points, indices, signs).
// Conventions: lengths in Å, weights (squared radii) in Å², angles in radians
// inside the code and degrees at the edges. See papers/conventions.md §3.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <limits>

namespace skinmesh {

/// A point or vector in R^3 (Å).
using Vec3 = Eigen::Vector3d;
/// A 3x3 matrix (projectors, quadric forms).
using Mat3 = Eigen::Matrix3d;

/// pi, the one definition of the project, and the radians of one degree
/// (angles are radians inside the code and degrees at its edges).
// Spelled out, not std::numbers::pi: the fuzz build compiles the one file that
// includes gemmi as C++17 (tests/fuzz/CMakeLists.txt). The same double.
inline constexpr double kPi = 3.141592653589793238462643383279502884;
inline constexpr double kDegree = kPi / 180.0;

/// Index into a flat array (vertices, simplices, mesh elements).
using Index = std::uint32_t;
/// The invalid index value.
inline constexpr Index kInvalidIndex = std::numeric_limits<Index>::max();

/// Sign of a predicate: the result of every combinatorial decision.
/// After symbolic perturbation the value Zero never comes back.
enum class Sign : int { Negative = -1, Zero = 0, Positive = 1 };

/// Sign of a double (no tolerance).
inline Sign sign_of(double x) { return x > 0 ? Sign::Positive : (x < 0 ? Sign::Negative : Sign::Zero); }
/// Reverses a sign.
inline Sign operator-(Sign s) { return static_cast<Sign>(-static_cast<int>(s)); }

}  // namespace skinmesh

// skin/mixed_cell_distance.h: how far a point lies outside a mixed cell, the
// membership test of critical points (morse/critical_points) and of the
// singular-skin refusal (skin/singular_skin).
// Notes: papers/morse/critical_points.md ("Flat tetrahedra", "Slivers")
#pragma once

#include <span>

#include "core/types.h"
#include "skin/mixed_complex.h"

namespace skinmesh::skin {

/// Distance (Å, 0 inside) by which p lies outside the mixed cell c, the test
/// critical_points() uses to keep a candidate. Triangle and tetrahedron cells
/// are tested in their dual form mu_X = (X + V_X) / 2 (s = 1/2): p = (x + v) / 2
/// with x in the simplex X and v in its Voronoi face, measured against the
/// simplex itself (exact orientation tests) and the foci of the adjacent
/// tetrahedra; a triangle's Voronoi edge is oriented (each coface bounds it on
/// the side of its apex) and a flat (sliver) coface's focus is first moved into
/// the slab its neighbours allow (papers/morse/critical_points.md "Flat
/// tetrahedra"). The half-space form (MixedComplex::violation) is ill-conditioned
/// for a sliver tetrahedron: its facet planes are almost parallel and their
/// offsets are ratios of rounding errors, so the widened cell is an unbounded
/// slab (papers/morse/critical_points.md "Slivers"). Vertex and edge cells use
/// the half-space form.
double cell_distance(const MixedComplex& mc, Index c, const Vec3& p);
/// The same for cell c given as X with its planes (MixedComplex::cell_value()
/// and planes_into(), for scans that keep neither). Only vertex and edge
/// cells read the planes: a triangle's and a tetrahedron's may be empty.
double cell_distance(const MixedComplex& mc, Index c, const MixedCell& X, const Vec3& p,
                     std::span<const CellPlane> planes);

}  // namespace skinmesh::skin

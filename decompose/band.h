// decompose/band.h: the strip of triangles that closes the band between a slab's
// parked rim and its upper cut curve (papers/decompose/README.md, "The
// band's strip"): the triangulation of an annulus between two closed polylines
// without new vertices that maximises the smallest angle, by dynamic
// programming over the two cyclic sequences (then the least sum of a
// penalty of small angles among the strips of that smallest angle) — the
// contour-stitching problem of surface reconstruction from serial sections
// (Fuchs, Kedem & Uselton 1977; Christiansen & Sederberg 1978), here with
// the smallest angle as the objective and outward orientation as a
// constraint.
// Notes: papers/decompose/README.md ("The band's strip")
#pragma once

#include <array>
#include <vector>

#include "core/types.h"

namespace skinmesh::decompose {

/// One triangle of a strip: indices into the concatenation of the two
/// polylines (i < rim size: rim vertex i; else curve vertex i - rim size),
/// counter-clockwise about the outward normal.
using StripTriangle = std::array<Index, 3>;

/// Triangulates the annulus between the closed polylines `rim` and `curve`
/// (positions in Å, each with its unit outward normal), both given with the
/// annulus on their left seen from outside — so they run in opposite senses
/// around it, as a slab's parked rim and its upper cut curve (oriented by
/// n × e) do. Every triangle joins an edge of one polyline to a vertex of the
/// other; the rim's edges i -> i+1 and the curve's edges j -> j+1 are each in
/// exactly one triangle, as that triangle's own edge, so the strip glues to
/// both sides. Among such strips it returns one that maximises the smallest
/// angle, subject to every triangle facing outwards at its three corners
/// (its normal on the positive side of each corner's normal), and among
/// those one that minimises the sum over its triangles of 1 / sin² of their
/// smallest angles: the bottleneck alone leaves every other triangle free
/// to be as poor as it, and a strip twisted across the band by a few
/// samples is as good as a straight one. The strip's connecting edge at rim
/// vertex 0 ends at the curve vertex nearest to it or one of the two on
/// either side of that one (the best of the five). The search is
/// O(|rim| · |curve|) per start over a corridor of states whose arc-length
/// fractions differ by at most `corridor` (1: all states; widened to 1 if no
/// strip is found inside it). Returns an empty vector if no outward strip
/// exists.
/// Throws std::invalid_argument if a polyline has fewer than three vertices
/// or a normal per vertex is missing.
std::vector<StripTriangle> strip_triangulation(const std::vector<Vec3>& rim, const std::vector<Vec3>& rim_normals,
                                               const std::vector<Vec3>& curve, const std::vector<Vec3>& curve_normals,
                                               double corridor = 1.0);

}  // namespace skinmesh::decompose

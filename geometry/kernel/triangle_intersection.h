// geometry/kernel/triangle_intersection.h: exact intersection tests between closed
// segments and triangles in R^3, for the self-intersection check of
// geometry/check/mesh_checks. Every decision is an exact orient3d/orient2d sign
// (geometry/kernel/predicates.h); no tolerance anywhere.
//
// Method: the classic orientation-based test (Möller 1997; Guigue & Devillers
// 2003): first the vertices of each triangle against the plane of the other
// (all strictly on one side: disjoint), then edge-against-triangle tests, where
// a segment crossing the plane of a triangle hits it iff the three orientations
// of the segment's line with the triangle's edges do not have strictly opposite
// signs; coplanar cases are decided in 2D after dropping the coordinate along
// which the triangle projects without degenerating (exactly checked with orient2d).
// Two closed triangles meet iff an edge of one meets the other (the intersection
// is convex, and an extreme point of it lies on an edge of one of them).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "core/types.h"

namespace skinmesh::geometry {

/// True iff a, b, c are collinear (coincident points included), decided
/// exactly: all three coordinate projections have orient2d == Zero.
/// Such a triangle has zero area. Throws nothing.
bool is_degenerate_triangle(const Vec3& a, const Vec3& b, const Vec3& c);

/// True iff the closed segment [p, q] and the closed triangle abc share a point
/// (touching at an endpoint, an edge or a vertex counts). p == q is allowed (a
/// point). Exact. Pre: abc not degenerate; a degenerate abc is detected when it
/// matters and throws std::invalid_argument.
bool segment_intersects_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b, const Vec3& c);

/// True iff the closed triangles (a0, a1, a2) and (b0, b1, b2) share a point
/// (touching counts). Orientation of the triangles is irrelevant. Exact. Pre:
/// neither triangle is degenerate (std::invalid_argument when it matters).
bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                         const Vec3& b2);

/// For two mesh triangles that share the vertex s, (s, a1, a2) and (s, b1, b2):
/// true iff they meet anywhere else than at s. Exact. This holds iff [a1, a2]
/// meets the second triangle or [b1, b2] meets the first (the intersection is a
/// convex set containing s; walk from s to its far end). Pre: both triangles
/// not degenerate.
bool triangles_intersect_beyond_vertex(const Vec3& s, const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2);

/// For two mesh triangles that share the edge uv, (u, v, a) and (u, v, b), in
/// either orientation: true iff they overlap beyond the segment [u, v], which
/// happens iff they are coplanar and a, b lie on the same side of the line uv
/// (non-coplanar triangles meet only on the common line, i.e. in [u, v]).
/// Exact. Pre: both triangles not degenerate.
bool triangles_intersect_beyond_edge(const Vec3& u, const Vec3& v, const Vec3& a, const Vec3& b);

/// Intersection of two mesh triangles given by vertex indices into `positions`,
/// ignoring what their shared vertices imply: with no shared index,
/// triangles_intersect(); one shared index, triangles_intersect_beyond_vertex();
/// two, triangles_intersect_beyond_edge(); three (the same triangle twice):
/// true. Distinct indices at equal positions are distinct vertices (so they
/// make the triangles intersect). Pre: indices in range, neither triangle
/// degenerate nor with a repeated index.
bool mesh_triangles_intersect(const std::array<Index, 3>& t, const std::array<Index, 3>& u,
                              std::span<const Vec3> positions);

}  // namespace skinmesh::geometry

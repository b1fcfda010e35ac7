// refine/restricted_delaunay.h: surface Delaunay balls and the restricted
// Delaunay test for triangles of a mesh with vertices on the skin.
// Cheng & Shi 2004 §2.2 ("Restricted Delaunay triangulation"), §4.3 (edge
// flipping keeps it); papers/front/open_questions.md Q9.2.
// Notes: papers/refine/restricted_delaunay.md
#pragma once

#include "geometry/types.h"
#include "skin/skin_surface.h"

namespace skinmesh::refine {

/// Circumcentre (Å) of triangle abc in its plane. Pre: abc not degenerate.
Vec3 circumcentre(const Vec3& a, const Vec3& b, const Vec3& c);

/// The surface Delaunay ball of triangle abc (vertices on the skin): its
/// centre m is the point where the line through the circumcentre along the
/// triangle normal (the line of the dual Voronoi edge) meets the skin, the
/// intersection nearest to the circumcentre within distance 2R (R the
/// circumradius); its radius is |m - a|. `cell` is a mixed-cell hint on entry
/// and m's cell on exit. Returns false if the line does not meet the skin
/// there (a triangle far from restricted Delaunay).
bool surface_delaunay_centre(const skin::SkinSurface& skin, const Vec3& a, const Vec3& b,
                             const Vec3& c, Vec3& m, Index& cell);

}  // namespace skinmesh::refine

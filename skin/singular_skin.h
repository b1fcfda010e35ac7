// skin/singular_skin.h: the refusal of singular (and nearly singular) skins,
// shared by every mesher: a skin with a cone point, or a neck, gap or cavity
// far below the molecule's size, has no mesh of bounded size under [L]/[U].
// Notes: papers/mesher/pipeline.md ("Singular skins")
#pragma once

#include "skin/skin_surface.h"

namespace skinmesh::skin {

/// Refuses a skin that is singular or within kSingularScale · L of a
/// singular one (L the mixed complex's length scale, Å): a simplex X (edge,
/// triangle or tetrahedron of the regular triangulation) whose orthosphere
/// weight w_X is at most 2 eps² in absolute value, eps = kSingularScale · L,
/// with its focus z_X within eps of its mixed cell. There the skin has a cone
/// point (two balls touching, three or four balls meeting at one point) or a
/// neck, gap or cavity of radius sqrt(|w_X| / 2) <= eps: rho falls to that
/// radius and no mesh of bounded size resolves it. Throws InputError naming
/// the atoms (input order, 1-based) and what to change. papers/mesher/pipeline.md,
/// "Singular skins". Shared by the sweep (mesher/pipeline) and the dynamic-skin
/// baseline (dynamic/dynamic_skin). The cells are tested on up to `threads`
/// threads (0: every core); the error is the one a single loop raises.
void require_non_singular(const skin::SkinSurface& skin, int threads = 1);

}  // namespace skinmesh::skin

#pragma once
/// \file bump_move.h
/// Moves one fixed vertex of a valid map to a new UV by a smooth bump deformation of the plane
/// around it, so that a map already optimised can be optimised again from there (`ctmap serve`'s
/// incremental re-map, issue 15) instead of from the paper's embedding.
#include <limits>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// Displaces every UV within radius r of `uv[vertex]` by d * (1 - s^2)^2 (d = target - uv[vertex],
/// s = distance / r), r being the distance to the nearest other vertex of `fixed`, so those stay
/// bitwise where they are; `uv[vertex]` becomes `target` exactly. The deformation of the plane is a
/// diffeomorphism when |d| * 1.54 / r < 1; this requires r >= 3.1 |d| (a Lipschitz constant of the
/// displacement at most 1/2). The piecewise-linear map can still fold a triangle that is large
/// against r: the caller checks the result with exact predicates (optimise_isometric does on entry).
/// A longer move is made in up to `max_steps` equal bumps, the reach measured again before each.
/// `max_radius` caps r, so that only UVs within it of the vertex move (a local edit).
/// \pre vertex is an index of uv. \return false (uv unchanged) if the move needs more steps or a
///      displaced UV would leave [lo, hi].
bool bump_move(std::vector<Vec2>& uv, int vertex, const Vec2& target, const std::vector<int>& fixed, const Vec2& lo,
               const Vec2& hi, int max_steps = 8,
               double max_radius = std::numeric_limits<double>::infinity());

}  // namespace ctmap

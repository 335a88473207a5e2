#pragma once
/// \file line_search.h
/// The distortion optimiser's line search (refine/isometric.h, beyond paper §2.4): along a
/// direction, from 0.9 of the largest flip-free step (flip_free_step.h) of the map's faces and
/// the scaffold's (scaffold.h) or the whole step, halving until the objective drops (the energy,
/// the box barrier and the scaffold's), the exact orientation predicates agree on every triangle
/// of the map and of the scaffold, and the border guard accepts the trial map (its UV border
/// simple and inside the rectangle). Every accepted map is valid by itself: all triangles of one orientation and a
/// simple border make the map of a disc one-to-one, whatever the path to it.
#include <vector>

#include "ctmap/refine/border_guard.h"
#include "ctmap/refine/isometric_problem.h"
#include "ctmap/refine/scaffold.h"

namespace ctmap {

/// What the line search found.
struct LineSearchResult {
    bool accepted = false;
    double step = 0;           ///< the step taken (the last tried if none was accepted)
    double bound = 0;          ///< the flip-free bound of the map's faces and the scaffold's
    double scaffold_bound = 0; ///< the scaffold's alone
    double energy = 0;         ///< the map's energy (against the frames given) at the accepted step
    double objective = 0;      ///< that with the barrier and the scaffold
    int halvings = 0, exact_rejections = 0, border_rejections = 0;
};

/// Searches along `d` from `uv` (objective `e0` there) with the faces of `p` measured against
/// `frames`; the accepted map is left in `trial`. `scaffold`: the current map's scaffold (null:
/// none); `check_border` off checks only that the border stays in the rectangle (tests, to show
/// what the guard prevents).
/// \pre uv is valid (every triangle of p's orientation, its border simple, the scaffold's
///      triangles counter-clockwise); d is zero for vertices without unknowns; trial has uv's size.
LineSearchResult flip_free_line_search(const IsometricProblem& p, const std::vector<FaceFrame>& frames,
                                       const Scaffold* scaffold,
                                       const BorderGuard& guard, bool check_border,
                                       const std::vector<Vec2>& uv, const std::vector<Vec2>& d, double e0,
                                       std::vector<Vec2>& trial);

}  // namespace ctmap

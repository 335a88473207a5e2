#pragma once
/// \file line_search.h
/// The distortion optimiser's line search (refine/isometric.h, beyond paper §2.4): along a
/// direction, from 0.9 of the largest flip-free step (flip_free_step.h) or the whole step, halving
/// until the objective (the energy and the box barrier) drops, the exact orientation predicates
/// agree on every triangle and the border guard accepts the trial map. Where the guard refuses a
/// step because two border edges would meet, the vertices of those edges are held where they are
/// (their direction zeroed) and the search starts again, at most 8 times: a contact stops the
/// border there, not the whole map.
#include <vector>

#include "ctmap/refine/border_guard.h"
#include "ctmap/refine/isometric_problem.h"

namespace ctmap {

/// What the line search found.
struct LineSearchResult {
    bool accepted = false;
    double step = 0;          ///< the step taken (the last tried if none was accepted)
    double energy = 0;        ///< the map's energy (against the frames given) at the accepted step
    double objective = 0;     ///< that with the barrier
    int halvings = 0, exact_rejections = 0, border_rejections = 0;
    int holds = 0;            ///< times border vertices were held at a contact
    std::vector<int> held;    ///< those vertices (their direction zeroed)
};

/// Searches along `d` from `uv` (objective `e0` there) with the faces of `p` measured against
/// `frames`; the accepted map is left in `trial`. `check_border` off checks only that the border
/// stays in the rectangle (tests, to show what the guard prevents).
/// \pre uv is valid (every triangle of p's orientation, its border simple); d is zero for vertices
///      without unknowns; trial has uv's size.
LineSearchResult flip_free_line_search(const IsometricProblem& p, const std::vector<FaceFrame>& frames,
                                       const BorderGuard& guard, bool check_border, const std::vector<Vec2>& uv,
                                       std::vector<Vec2>& d, double e0, std::vector<Vec2>& trial);

}  // namespace ctmap

#pragma once
/// \file flip_free_step.h
/// The largest step along a direction that flips no triangle (Smith & Schaefer 2015, "Bijective
/// parameterization with free boundaries", §4): each UV triangle's signed area is a quadratic in
/// the step t, and the map stays valid for every t below the smallest positive root over all
/// triangles. Used by the distortion optimiser's line search (refine/isometric), beyond paper §2.4.
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// The smallest positive t at which some triangle of `faces` has zero signed area in the map
/// uv + t d (+infinity if none). Floating point: the optimiser backs off from it and checks the
/// step it takes with the exact predicates.
/// \pre uv.size() == d.size(); every face has its corners in range; every triangle of `uv` has
/// the orientation `sigma` (+1 counter-clockwise, -1 clockwise).
double max_flip_free_step(const std::vector<Tri>& faces, const std::vector<Vec2>& uv, const std::vector<Vec2>& d,
                          int sigma, bool parallel = true);

/// The smallest positive root of c + b t + a t^2 (+infinity if none), for c > 0 (the area now).
double smallest_positive_root(double a, double b, double c);

}  // namespace ctmap

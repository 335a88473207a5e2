#pragma once
/// \file morph_quality.h
/// How well a morph holds both shapes (issue 14 must-show 1): pairs on their target points, every
/// vertex on both surfaces, the target's detail kept (Hausdorff distance).
#include "ctmap/morph/morph_meshes.h"

namespace ctmap {

/// Distances in the target's units (source_off in the source's).
struct MorphQuality {
    double pair_error = 0;        ///< max over pairs: morphed source feature to its target point
    double target_off = 0;        ///< max over common vertices: weight-1 position to the target surface
    double source_off = 0;        ///< max over common vertices: weight-0 position to the source surface
    double hausdorff = 0;         ///< one-sided Hausdorff distance from the target to the weight-1 surface
    double target_mean_edge = 0;  ///< the target input's mean edge length
    double diagonal = 0;          ///< the target's bounding-box diagonal
};

/// Measures `m` (AABB-tree distances, surface_distance.h). `target` is the target as given.
MorphQuality measure_morph(const MorphResult& m, const TriMesh& target);

}  // namespace ctmap

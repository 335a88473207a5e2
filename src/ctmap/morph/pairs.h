#pragma once
/// \file pairs.h
/// The pairs file of `ctmap morph` (issue 14, DESIGN §4, paper §4): the same features on a source
/// and a target mesh.
#include <optional>
#include <string>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// One end of a pair: a mesh vertex (0-based, as in the file) or a 3D point on the surface.
struct PairEnd {
    int vertex = -1;            ///< -1 for a point
    std::optional<Vec3> point;  ///< when `vertex` is -1
};

/// A named feature on both meshes.
struct FeaturePair {
    std::string name;
    PairEnd source, target;
};

/// A parsed pairs file. (Charts, when they come, add a per-chart list beside `pairs`.)
struct PairSet {
    std::string path;  ///< the JSON file, for messages
    std::vector<FeaturePair> pairs;
};

/// Reads and checks a pairs file: JSON syntax (nesting bounded), `units` "mesh" if given, a
/// non-empty `pairs` array, each pair with a unique non-empty `name` and a `source` and `target`
/// that give exactly one of `vertex` (a non-negative integer) or `point` ([x, y, z], finite);
/// no two pairs at the same source or target vertex.
/// \throw BadInput naming the file and every violation with the pairs involved.
PairSet read_pairs(const std::string& path);

/// The same from text (`path` names it in messages).
PairSet parse_pairs(const std::string& text, const std::string& path);

/// The pairs as JSON text in the file's format (numbers in the shortest form that reads back exactly).
std::string pairs_to_json(const PairSet& pairs);

}  // namespace ctmap

#pragma once
/// \file morph_meshes.h
/// Mesh morphing with aligned features (paper §4, issue 14): the target is mapped once onto a
/// polygon (its border pairs at the corners), that map is the "image" the source is mapped onto
/// with every pair exact (the constrained pipeline, certified), and the two maps give a common
/// mesh whose every vertex lies on both surfaces.
#include <functional>
#include <string>
#include <vector>

#include "ctmap/map_texture.h"
#include "ctmap/morph/common_mesh.h"
#include "ctmap/morph/pairs.h"

namespace ctmap {

/// Options of `morph_meshes`.
struct MorphOptions {
    /// Options of both maps. The border mode is always fixed: both maps put their borders on the
    /// same polygon's sides, so that their domains agree.
    MapOptions map;
    /// Move the source by the similarity (rotation, uniform scale, translation) that best takes
    /// its pairs onto the target's (least squares, Umeyama 1991) before morphing, so that the
    /// morph changes shape, not pose or size. The target is never moved.
    bool align = true;
    bool resample = true;  ///< insert the target's vertices into the common mesh (common_mesh.h)
    double snap = -1;      ///< how far a pair's point may be off its surface (< 0: kDefaultSnapFraction of the diagonal)
    /// Called when a stage starts: "target map", "source map", "common mesh".
    std::function<void(const std::string& stage)> progress;
};

/// Wall-clock milliseconds per stage.
struct MorphTimings {
    double target_map = 0, source_map = 0, common_mesh = 0, total = 0;
};

/// The morph: one mesh, two shapes.
struct MorphResult {
    CommonMesh common;                   ///< mesh (source shape), target_position, uv
    std::vector<int> pair_vertex;        ///< per pair, its vertex of the common mesh (= of source_map.cut.mesh)
    std::vector<int> target_pair_vertex; ///< per pair, its vertex of target_map.cut.mesh
    std::vector<std::string> border_pairs;  ///< the border pairs in the order of both borders
    MapResult target_map, source_map;    ///< the two certified maps into the polygon
    /// The similarity applied to the source (`MorphOptions::align`; identity otherwise): the
    /// common mesh's weight-0 shape is the source moved by it.
    Eigen::Matrix4d alignment = Eigen::Matrix4d::Identity();
    MorphTimings timings_ms;
};

/// Morphs `source` into `target` with every pair aligned (paper §4).
/// \pre none beyond the types: every input is checked on entry.
/// \throw BadInput naming the pairs (and `source_file`, `target_file` or `pairs.path`): a mesh
///        that is not a disc (closed meshes need charts), a vertex out of range, a point off its
///        surface, two pairs at one vertex, a pair on one border only, fewer than 3 border pairs,
///        border pairs in different cyclic orders, or a pair layout the source cannot be cut
///        into; InternalError if a map fails its certificate.
MorphResult morph_meshes(const TriMesh& source, const TriMesh& target, const PairSet& pairs,
                         const MorphOptions& options = {}, const std::string& source_file = "source",
                         const std::string& target_file = "target");

/// The morphed shape at weight w in [0, 1]: (1 - w) source + w target, per vertex.
std::vector<Vec3> morph_frame(const CommonMesh& common, double w);

}  // namespace ctmap

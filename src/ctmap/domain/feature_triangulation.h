#pragma once
/// \file feature_triangulation.h
/// The image side of the cut (paper §2.3, Fig. 2): a constrained Delaunay triangulation of the
/// feature points, the border features joined in their order along the mesh border.
#include <array>
#include <string>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// Triangulation of the feature points in the plane of the texture (UV coordinates, v up, so
/// that counter-clockwise means the same as on the mesh; DESIGN §3). Indices are feature indices.
struct FeatureTriangulation {
    std::vector<Vec2> points;              ///< one per feature, UV
    std::vector<Tri> triangles;            ///< counter-clockwise in the chart's orientation (see `mirrored`)
    std::vector<std::array<int, 2>> edges; ///< every edge once, (a, b) with a < b
    std::vector<bool> edge_on_border;      ///< per edge: a border constraint (joins consecutive border features)
    std::vector<int> border;               ///< border features in the mesh border's order
    /// Per feature, its neighbours in counter-clockwise order around it (in the chart's
    /// orientation). For a border feature the list starts with the next border feature along the
    /// border and ends with the previous one.
    std::vector<std::vector<int>> neighbours;
    /// True when the image's border runs clockwise where the mesh's runs counter-clockwise: the
    /// whole map is mirrored (allowed); triangles and neighbour orders are then given in the
    /// mirrored sense so that they match the mesh.
    bool mirrored = false;
};

/// Options for `triangulate_features` (none yet: the messages name no file, issue 16).
struct TriangulateOptions {};

/// How messages name feature `i`: 'name' in quotes, or #i when it has none.
std::string feature_label(const std::vector<std::string>& names, int i);

/// Builds the constrained Delaunay triangulation of `points` (UV) with the border polygon
/// `border` (feature indices in the order the mesh border meets them) as constraints, keeping
/// only the triangles inside it.
/// \pre points are distinct and finite.
/// \throw BadInput naming the features if there are fewer than 3 border features, the border
///        polygon is not simple, an interior feature lies outside it (or on it), or `names` are
///        given and a problem is reported with them.
FeatureTriangulation triangulate_features(const std::vector<Vec2>& points, const std::vector<int>& border,
                                          const std::vector<std::string>& names,
                                          const TriangulateOptions& options = {});

}  // namespace ctmap

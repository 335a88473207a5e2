#pragma once
/// \file render_inputs.h
/// Everything a picture needs, read from files: the map (OBJ with UVs and patch groups), its
/// image, the features and, for the triangulation picture, the feature triangulation. Shared by
/// `ctmap render` and the demo gallery so both check their inputs the same way.
#include <optional>
#include <string>
#include <vector>

#include "ctmap/domain/feature_triangulation.h"
#include "ctmap/io/features.h"
#include "ctmap/io/image.h"
#include "ctmap/mesh.h"
#include "ctmap/render/render_map.h"

namespace ctmap {

/// The files of a picture. Empty strings mean "not given".
struct RenderFiles {
    std::string map;       ///< textured OBJ (required)
    std::string image;     ///< overrides the OBJ material's `map_Kd` (and the features file's `image`)
    std::string features;  ///< features.json (DESIGN §4): markers, and the triangulation picture
    /// A map with several charts (an OBJ with a material per chart, issue 13): draw only the
    /// chart of this name (its material, `chart_<name>`), with its own image; empty: every chart,
    /// each textured with its material's image.
    std::string chart;
};

/// The inputs read and checked; `scene()` points into this object, so keep it alive while drawing.
struct RenderInputs {
    TexturedMesh mesh;
    std::optional<Image> image;
    std::string image_path;
    FeatureSet features;
    std::vector<int> feature_vertex;  ///< per feature, its vertex of `mesh`
    std::vector<Vec2> feature_uv;     ///< per feature, its UV (DESIGN §3, `image_to_uv`)
    std::optional<FeatureTriangulation> triangulation;
    std::vector<Image> chart_images;  ///< per chart, its material's image (OBJ with several charts)

    RenderScene scene() const;
};

/// Reads what the `modes` need from `files`: the OBJ (texture coordinates required except for
/// `paths`; patch groups for `paths`), the image (`--image`, else the material's `map_Kd`, else
/// the features file's `image`; required for textured, uv and triangulation, used for the
/// checker's aspect when present), the features (required for triangulation), and the feature
/// triangulation (border features in the order the mesh border meets them, paper §2.3).
/// A feature given as a 3D point is found as the vertex of the OBJ at that point (ctmap map
/// inserts one there).
/// \throw BadInput naming the file and the problem: an unreadable or broken file, an OBJ without
///        UVs or patches where the mode needs them, no image where one is needed, features that
///        are not on the mesh, a mesh that is not a disc (triangulation).
RenderInputs read_render_inputs(const RenderFiles& files, const std::vector<RenderMode>& modes);

}  // namespace ctmap

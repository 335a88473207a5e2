#pragma once
/// \file features.h
/// The features file (DESIGN §4, paper step 1): the same features on the mesh and on the image.
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// One feature: a mesh vertex (or a 3D point on the surface) and its image point.
struct Feature {
    std::string name;
    int vertex = -1;            ///< mesh vertex (0-based, as in the mesh file), or -1 for a point
    std::optional<Vec3> point;  ///< a 3D point on the surface, when `vertex` is -1
    Vec2 image{0, 0};           ///< image point in the file's units (pixels after `resolve_units`)
};

/// A parsed features file.
struct FeatureSet {
    std::string path;                             ///< the JSON file
    std::string image;                            ///< image path resolved against the JSON's folder, or empty
    std::optional<std::array<int, 2>> image_size;  ///< `image_size: [W, H]`, if given
    std::string units = "pixels";                 ///< "pixels" or "uv"
    std::vector<Feature> features;
};

/// Reads and checks a features file: JSON syntax, fields and types, finite numbers, units, unique
/// names and vertices, distinct image points.
/// \throw BadInput naming the file and every violation with the features involved.
FeatureSet read_features(const std::string& path);

/// Parses a features document from text (`path` only names it in messages and resolves `image`).
/// \throw BadInput as read_features.
FeatureSet parse_features(const std::string& text, const std::string& path);

/// Converts image points to pixels for an image of `width` x `height` (UV = (x/W, 1-y/H), DESIGN
/// §3) and checks that every point lies inside the image, [0, W] x [0, H].
/// \pre width > 0, height > 0.
/// \throw BadInput naming the features outside the image.
void resolve_units(FeatureSet& fs, int width, int height);

/// Resolves the image of a features set by the rule of `ctmap map` (issue 4): `image_arg` (the
/// --image option) if given, else the file's `image`, else its `image_size`; reads the image for
/// its size (checking it against `image_size` when both are given), then converts the features'
/// image points to pixels (`resolve_units`).
/// \return the image path (empty when only `image_size` gave the size); width and height set.
/// \throw BadInput naming the file: no image at all, an unreadable image, a size mismatch, or
///        points outside the image.
std::string resolve_feature_image(FeatureSet& fs, const std::string& image_arg, int& width, int& height);

/// How far a 3D point feature may lie off the surface by default, as a fraction of the mesh's
/// bounding-box diagonal: coordinates printed with 4 decimals are accepted (issue 17).
constexpr double kDefaultSnapFraction = 1e-4;

/// Checks the features against the mesh: every vertex index exists, every 3D point lies on the
/// surface within `max_distance` (in the mesh's units; negative: kDefaultSnapFraction of the
/// bounding-box diagonal). The map puts each point at the closest point of the surface.
/// \return the largest distance of a point feature from the surface (0 without point features).
/// \throw BadInput naming the features, the mesh file and the distance.
double check_features_on_mesh(const FeatureSet& fs, const TriMesh& mesh, const std::string& mesh_file,
                              double max_distance = -1);

/// Each feature's vertex on a map written by `ctmap map` (or any mesh holding the features): its
/// own vertex, or for a 3D point the nearest vertex, which must lie within `snap_tolerance`.
/// \throw BadInput naming `map_file` if a point has no vertex that close.
std::vector<int> feature_vertices_on_map(const FeatureSet& fs, const TriMesh& mesh, const std::string& map_file,
                                         double max_distance = -1);

/// The tolerance `check_features_on_mesh` uses for `max_distance` on `mesh`.
double snap_tolerance(const TriMesh& mesh, double max_distance = -1);

/// The features as JSON text in the format of DESIGN §4 (pixels).
std::string features_to_json(const FeatureSet& fs);

}  // namespace ctmap

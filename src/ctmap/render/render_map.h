#pragma once
/// \file render_map.h
/// Pictures of a texture map, as in the paper's figures: the textured mesh (Fig. 5-7), a checker
/// texture showing the distortion (Fig. 1i), the UV layout over the image (Fig. 1e/g), the cut
/// paths on the mesh (Fig. 1d) and the feature triangulation over the image (Fig. 1c). Drawn by
/// OpenGL off-screen (gl_context.h): a real rasterizer with a depth buffer, multisampling and
/// mipmapped, linearly filtered textures.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ctmap/domain/feature_triangulation.h"
#include "ctmap/io/image.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// Where the camera looks from (3D modes). The mesh's own axes: front looks along -z from +z
/// with +y up (the OBJ convention, and nefertiti's face), side from +x, back from -z, top from
/// +y with -z up, three-quarter from between front, side and a little above; left from -x, bottom
/// from -y with +z up (the other halves of a closed mesh's two charts, issue 13).
enum class RenderView { front, side, back, top, three_quarter, left, bottom };

/// What is drawn.
enum class RenderMode {
    textured,       ///< the mesh, shaded and textured with the image (Fig. 5-7)
    checker,        ///< the mesh with a checker texture in UV space: its distortion (Fig. 1i)
    uv,             ///< the UV triangles, patch borders and features over the image (Fig. 1e/g)
    paths,          ///< the mesh, its patches, the cut paths and the features (Fig. 1d)
    triangulation,  ///< the feature triangulation over the image (Fig. 1c)
};

/// True for the modes that draw the mesh in 3D (textured, checker, paths); the others draw the
/// image plane.
bool is_3d(RenderMode mode);

/// Names as the command line spells them ("three-quarter", ...) and back.
/// \throw BadInput naming the unknown word and the choices.
RenderView parse_render_view(const std::string& name);
RenderMode parse_render_mode(const std::string& name);
std::string to_string(RenderView view);
std::string to_string(RenderMode mode);

/// Options of `render_map`.
struct RenderOptions {
    int width = 1024;   ///< pixels, in [kMinSize, kMaxSize]
    int height = 1024;
    RenderView view = RenderView::front;
    RenderMode mode = RenderMode::textured;
    std::array<std::uint8_t, 4> background{255, 255, 255, 255};  ///< RGBA; alpha 0 gives a transparent PNG
    bool shading = true;         ///< headlight diffuse shading in 3D; off: the texture's own colours
    int samples = 4;             ///< multisampling (antialiasing); 1 = none
    double line_width = 0;       ///< pixels; 0 = automatic (scales with the picture)
    double marker_radius = 0;    ///< feature markers, pixels; 0 = automatic
    int checker_cells = 12;      ///< checker squares across the map's extent in the image (square in image pixels)
    bool whole_image = false;    ///< image-plane modes: show the whole image, not just around the map

    static constexpr int kMinSize = 16;
    static constexpr int kMaxSize = 8192;
};

/// What to draw. Only `mesh` is needed by every mode except triangulation.
struct RenderScene {
    const TexturedMesh* mesh = nullptr;  ///< the map: UVs per corner (OBJ convention, v up), patches for `paths`
    const Image* image = nullptr;        ///< the texture (textured, uv, triangulation); its size sets the UV aspect
    /// Several charts (issue 13): per chart id of `mesh->chart`, its image (textured mode); empty:
    /// `image` for every face.
    std::vector<const Image*> chart_images;
    std::vector<int> feature_vertex;     ///< per feature, its vertex of `mesh` (markers in 3D modes)
    std::vector<Vec2> feature_uv;        ///< per feature, its UV (markers in the image-plane modes)
    const FeatureTriangulation* triangulation = nullptr;  ///< for `triangulation` (points in UV)
};

/// The camera of a picture: world point -> pixel, exactly the transform the renderer gives
/// OpenGL (in single precision there), so tests can find where a vertex lands.
struct Camera {
    Eigen::Matrix4d view = Eigen::Matrix4d::Identity();        ///< world -> eye
    Eigen::Matrix4d projection = Eigen::Matrix4d::Identity();  ///< eye -> clip
    int width = 0, height = 0;
    Vec3 eye = Vec3::Zero();     ///< camera position (3D modes)
    Vec3 target = Vec3::Zero();  ///< the point looked at: the bounding sphere's centre (3D modes)
    double fovy = 0;             ///< vertical field of view, radians (3D modes)
    bool perspective = false;  ///< 3D modes; the image-plane modes are orthographic
    /// In the image-plane modes, the world point of UV (u, v) is (u * aspect, v, 0) with aspect
    /// the image's width / height, so that image pixels stay square.
    double uv_aspect = 1;

    /// Pixel position of world point `p`: x right and y down from the top-left corner of the
    /// picture, continuous (pixel (i, j) covers [i, i+1] x [j, j+1]); z is the window depth in [0, 1].
    Vec3 project(const Vec3& p) const;
    /// Pixel position of UV (u, v) in the image-plane modes.
    Vec3 project_uv(const Vec2& uv) const { return project(Vec3(uv.x() * uv_aspect, uv.y(), 0)); }
};

/// The camera `render_map` uses for `scene` and `options`: in 3D, a perspective camera on the
/// chosen side whose view holds the mesh's bounding sphere (centre of the bounding box, radius
/// of the farthest vertex) with a small margin; in the image plane, the image's rectangle fitted
/// into the picture with a margin.
/// \pre as render_map.
Camera render_camera(const RenderScene& scene, const RenderOptions& options);

/// The part of the image plane the image-plane modes show, in their world coordinates (u *
/// aspect, v): the map's UV bounding box (the triangulation's for `triangulation`) grown by 15%
/// on each side, or the whole image with `whole_image`. Its aspect gives a picture with no empty
/// bands. \pre as render_map, an image-plane mode.
Eigen::AlignedBox2d image_plane_region(const RenderScene& scene, const RenderOptions& options);

/// The colour of feature i's marker (distinct hues by the golden angle), and of the blobs that
/// tests paint at feature points.
std::array<std::uint8_t, 3> feature_colour(int i);

/// The two colours of the checker texture, and the texture itself: `cells_x` squares across,
/// `cells_y` down, `cell` pixels each (RGBA). The renderer repeats a 2 x 2 tile of it over UV
/// space, scaled so that `RenderOptions::checker_cells` squares span the map.
inline constexpr std::array<std::uint8_t, 3> kCheckerDark{45, 85, 190};
inline constexpr std::array<std::uint8_t, 3> kCheckerLight{240, 240, 235};
Image checker_texture(int cells_x, int cells_y, int cell = 32);

/// Draws `scene` as described by `options.mode` and returns the picture (RGBA, rows top to
/// bottom, `options.width` x `options.height`).
/// \pre the mode's inputs are in `scene`: a mesh with UVs for textured, checker and uv; an image
///      for textured, uv and triangulation; patches (`mesh->patch`) for paths; a triangulation
///      for triangulation. Feature vertices index `mesh`.
/// \throw BadInput for a missing input of the mode, a size out of range or an image larger than
///        the GPU's texture limit; InternalError if OpenGL cannot be set up or fails.
Image render_map(const RenderScene& scene, const RenderOptions& options);

/// GL_RENDERER and GL_VERSION of the off-screen context (for reports and benchmarks).
std::string render_backend();

}  // namespace ctmap

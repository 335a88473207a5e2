#pragma once
/// \file bake_texture.h
/// `ctmap bake` (issue 42): the photo, aligned by the map's features, painted into another UV
/// layout of the mesh (the user's own: a rigged head's, laid out for painting). For every texel
/// of ONTO's UV triangles: the surface point it stands for, the map's texture coordinate there,
/// and the photo's colour at that coordinate.
///
/// When ONTO is the mesh the map was computed from, the transfer is exact: each map face records
/// the input face it lies in (TexturedMesh::input_face), so a texel's point is a barycentric point
/// of a known input face, found among that face's pieces with the certificate's exact orientation
/// predicate (a point on a cut path belongs to the first piece that holds it, one side only).
/// Otherwise (another tessellation of the same surface) the closest point of the map's surface.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "ctmap/io/image.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// How a texel finds its point on the map.
enum class BakeTransfer {
    automatic,  ///< exact when ONTO is the map's input mesh (checked), else closest
    exact,      ///< required exact: BadInput when ONTO is not the map's input mesh
    closest,    ///< the closest point of the map's surface (CGAL's AABB tree)
};

/// Options of `bake_texture`.
struct BakeOptions {
    int width = 0, height = 0;  ///< the texture's size; 0: the first photo's
    int padding = 8;            ///< texels the islands' border colours grow outward (0: none)
    /// Closest transfer: a texel whose point is farther than this from the map's surface is left
    /// empty and counted (< 0: 1% of ONTO's bounding-box diagonal).
    double max_distance = -1;
    BakeTransfer transfer = BakeTransfer::automatic;
    /// The UDIM tile baked (its corner in UV: (u, v) = (t % 10, t / 10) for tile 1001 + t);
    /// faces of other tiles are left out. (0, 0): the unit square.
    Vec2 tile = Vec2::Zero();
    /// Called as rows are done (done of total), from any thread.
    std::function<void(int done, int total)> progress;
};

/// What a bake did.
struct BakeStats {
    bool exact = false;          ///< the transfer was exact (ONTO is the map's input mesh)
    std::string not_exact;       ///< why not, when it was not
    long long covered = 0;       ///< texels in a UV triangle of ONTO, coloured
    long long written_twice = 0; ///< texels strictly inside two UV triangles (overlapping islands: the later face wins)
    long long too_far = 0;       ///< closest transfer: texels left empty, their point beyond max_distance
    long long padded = 0;        ///< texels the padding filled
    int faces = 0;               ///< ONTO's faces in the tile
    double max_distance = 0;     ///< the distance used (closest transfer)
};

/// The baked texture: RGBA, alpha 0 where nothing was written (not covered, not padded);
/// `covered` has 1 per texel a UV triangle covers.
struct BakeResult {
    Image texture;
    std::vector<std::uint8_t> covered;
    BakeStats stats;
};

/// Bakes `photos` through `map` into `onto`'s UV layout.
/// \pre `map` has UVs (OBJ's convention, TexturedMesh) and, for the exact transfer, `input_face`
///      (map_texture's, or read from ctmap's OBJ; when it is missing and ONTO's vertices are the
///      map's first ones it is recomputed, input_faces.h); `photos` holds one RGBA image, or one
///      per chart of `map` (TexturedMesh::chart); `onto` has UVs. Only ONTO's faces whose UVs lie in
///      the tile are baked (the others belong to other UDIM tiles: udim_tiles checks the layout).
/// \throw BadInput naming "map" or "onto" (callers put their file names in): no UVs, a degenerate
///        UV triangle (zero area, exact predicate), fewer photos than charts, a map with no face of
///        nonzero area, an exact transfer asked for on another mesh (ONTO's vertices not the map's
///        first ones within 1e-6 of the diagonal, a map face not inside its recorded ONTO face, or
///        the map's faces not tiling an ONTO face's area within 1e-4).
BakeResult bake_texture(const TexturedMesh& map, const std::vector<Image>& photos, const TexturedMesh& onto,
                        const BakeOptions& options = {});

/// The UDIM tiles `onto`'s UV triangles lie in (1001 + u + 10 v for the tile [u, u+1] x [v, v+1]),
/// sorted; {1001} for a layout in the unit square. A triangle on a tile's border belongs to it.
/// \throw BadInput naming "onto": no UVs, a non-finite UV, a triangle across tiles, a tile left
///        of u = 0, below v = 0 or right of u = 10 (no UDIM number).
std::vector<int> udim_tiles(const TexturedMesh& onto);

}  // namespace ctmap

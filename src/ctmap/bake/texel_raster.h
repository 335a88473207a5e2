#pragma once
/// \file texel_raster.h
/// Which texels of a texture a UV layout covers (issue 42): a texel belongs to a UV triangle
/// when its centre lies in the triangle, decided with the certificate's exact orientation
/// predicate, so a centre on an edge two triangles share is on that edge for both (never in a
/// gap, never counted as an overlap); then the padding that grows each island's colours outward.
#include <cstdint>
#include <functional>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// How a texel is held (TexelRaster::claim).
enum class TexelClaim : std::uint8_t {
    none = 0,      ///< in no triangle
    edge = 1,      ///< its centre is on a triangle's edge or corner
    interior = 2,  ///< its centre is strictly inside a triangle
};

/// A texture of `width` x `height` texels, rows top to bottom; texel (x, y) has its centre at
/// texel coordinates (x + 0.5, y + 0.5) and at UV ((x + 0.5) / W, 1 - (y + 0.5) / H) + tile.
struct TexelGrid {
    int width = 0, height = 0;
    Vec2 tile = Vec2::Zero();  ///< the UDIM tile's corner (0, 0 for [0, 1]^2)
    /// Texel coordinates of `uv` (continuous: the texel centres at half integers).
    Vec2 texel_of(const Vec2& uv) const { return {(uv.x() - tile.x()) * width, (1.0 - (uv.y() - tile.y())) * height}; }
};

/// Calls `visit(face, x, y, claim)` for every texel centre of `grid` in the UV triangle
/// `uv_faces[face]` (corners in texel coordinates, `corners[face]`), for the faces in `faces`,
/// rows in parallel bands (TBB): within a row the faces come in the order of `faces`, so a later
/// face's visit follows an earlier one's for the same texel. `row_done` is called once per band
/// with the number of rows finished so far (for progress lines), from any thread.
/// \pre no triangle is degenerate.
void raster_texels(const TexelGrid& grid, const std::vector<std::array<Vec2, 3>>& corners, const std::vector<int>& faces,
                   const std::function<void(int face, int x, int y, TexelClaim claim)>& visit,
                   const std::function<void(int rows_done)>& row_done = {});

/// Grows the covered texels' colours outward by `padding` texels: each pass gives every empty
/// texel next to a filled one (8 neighbours) the mean of its filled neighbours, so that a
/// filtered or mip-mapped read at an island's border takes no background. `covered[i]` says
/// whether texel i holds a colour; `rgba` has 4 bytes per texel. \return the texels filled.
long long pad_texels(int width, int height, int padding, std::vector<std::uint8_t>& rgba, const std::vector<std::uint8_t>& covered);

}  // namespace ctmap

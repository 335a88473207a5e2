#pragma once
/// \file photo_sampler.h
/// Reads a photo at a texture coordinate for the bake (issue 42): bilinear at the photo's own
/// resolution, and from a box-filtered mip pyramid where the bake minifies the photo (one baked
/// texel covers several photo pixels), blending the two nearest levels (trilinear), as a GPU
/// samples a mip-mapped texture.
#include <array>
#include <vector>

#include "ctmap/io/image.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// A photo and its mip levels, RGBA as floats in [0, 255].
class PhotoSampler {
public:
    /// \pre `photo` is RGBA (4 channels; io's read_image gives that) and not empty.
    /// \throw BadInput naming the photo otherwise.
    explicit PhotoSampler(const Image& photo);
    /// The colour at `uv` (OBJ's convention: u = x / W, v = 1 - y / H; pixel centres at half
    /// integers), bilinear, clamped to the photo's edge; `footprint` is how many photo pixels one
    /// baked texel spans (<= 1: level 0; else level log2(footprint), trilinear).
    std::array<float, 4> sample(const Vec2& uv, double footprint = 1) const;
    int width() const { return levels_.front().width; }
    int height() const { return levels_.front().height; }

private:
    struct Level {
        int width = 0, height = 0;
        std::vector<float> rgba;
    };
    std::array<float, 4> bilinear(const Level& level, const Vec2& uv) const;
    std::vector<Level> levels_;
};

}  // namespace ctmap

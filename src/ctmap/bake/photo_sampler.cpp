#include "ctmap/bake/photo_sampler.h"

#include <algorithm>
#include <cmath>

#include "ctmap/errors.h"

namespace ctmap {

PhotoSampler::PhotoSampler(const Image& photo) {
    if (photo.channels != 4 || photo.width <= 0 || photo.height <= 0 ||
        photo.pixels.size() != std::size_t(photo.width) * std::size_t(photo.height) * 4)
        throw BadInput(photo.path, "the photo must be a non-empty RGBA image");
    Level base;
    base.width = photo.width, base.height = photo.height;
    base.rgba.assign(photo.pixels.begin(), photo.pixels.end());
    levels_.push_back(std::move(base));
    // Each level halves the one below (a box filter; an odd size keeps its last row or column
    // out of the average), down to one pixel.
    while (levels_.back().width > 1 || levels_.back().height > 1) {
        const Level& a = levels_.back();
        Level b;
        b.width = std::max(1, a.width / 2), b.height = std::max(1, a.height / 2);
        b.rgba.resize(std::size_t(b.width) * std::size_t(b.height) * 4);
        for (int y = 0; y < b.height; ++y)
            for (int x = 0; x < b.width; ++x) {
                const int x0 = std::min(2 * x, a.width - 1), x1 = std::min(2 * x + 1, a.width - 1);
                const int y0 = std::min(2 * y, a.height - 1), y1 = std::min(2 * y + 1, a.height - 1);
                for (int c = 0; c < 4; ++c) {
                    auto at = [&](int xx, int yy) { return a.rgba[(std::size_t(yy) * std::size_t(a.width) + std::size_t(xx)) * 4 + std::size_t(c)]; };
                    b.rgba[(std::size_t(y) * std::size_t(b.width) + std::size_t(x)) * 4 + std::size_t(c)] =
                        0.25f * (at(x0, y0) + at(x1, y0) + at(x0, y1) + at(x1, y1));
                }
            }
        levels_.push_back(std::move(b));
    }
}

std::array<float, 4> PhotoSampler::bilinear(const Level& l, const Vec2& uv) const {
    double px = uv.x() * l.width - 0.5, py = (1.0 - uv.y()) * l.height - 0.5;
    if (!std::isfinite(px)) px = 0;  // (a point of a zero-area face: any colour of the photo, never a NaN index)
    if (!std::isfinite(py)) py = 0;
    const double fx = std::floor(px), fy = std::floor(py);
    const float tx = float(px - fx), ty = float(py - fy);
    auto clampi = [](double v, int n) { return int(std::clamp(v, 0.0, double(n - 1))); };
    const int x0 = clampi(fx, l.width), x1 = clampi(fx + 1, l.width);
    const int y0 = clampi(fy, l.height), y1 = clampi(fy + 1, l.height);
    const float* p00 = &l.rgba[(std::size_t(y0) * std::size_t(l.width) + std::size_t(x0)) * 4];
    const float* p10 = &l.rgba[(std::size_t(y0) * std::size_t(l.width) + std::size_t(x1)) * 4];
    const float* p01 = &l.rgba[(std::size_t(y1) * std::size_t(l.width) + std::size_t(x0)) * 4];
    const float* p11 = &l.rgba[(std::size_t(y1) * std::size_t(l.width) + std::size_t(x1)) * 4];
    std::array<float, 4> out{};
    for (int c = 0; c < 4; ++c)
        out[std::size_t(c)] = (1 - ty) * ((1 - tx) * p00[c] + tx * p10[c]) + ty * ((1 - tx) * p01[c] + tx * p11[c]);
    return out;
}

std::array<float, 4> PhotoSampler::sample(const Vec2& uv, double footprint) const {
    if (!(footprint > 1) || !std::isfinite(footprint) || levels_.size() == 1) return bilinear(levels_.front(), uv);
    const double lod = std::min(std::log2(footprint), double(levels_.size() - 1));
    const std::size_t lo = std::size_t(lod);
    const float t = float(lod - double(lo));
    const std::array<float, 4> a = bilinear(levels_[lo], uv);
    if (lo + 1 >= levels_.size() || t == 0) return a;
    const std::array<float, 4> b = bilinear(levels_[lo + 1], uv);
    std::array<float, 4> out{};
    for (std::size_t c = 0; c < 4; ++c) out[c] = (1 - t) * a[c] + t * b[c];
    return out;
}

}  // namespace ctmap

#include "ctmap/bake/texel_raster.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>

#include "ctmap/certify/certificate.h"

namespace ctmap {

void raster_texels(const TexelGrid& grid, const std::vector<std::array<Vec2, 3>>& corners, const std::vector<int>& faces,
                   const std::function<void(int, int, int, TexelClaim)>& visit, const std::function<void(int)>& row_done) {
    constexpr int kBand = 16;  // rows per task: each band's faces are visited in order
    const int bands = (grid.height + kBand - 1) / kBand;
    std::vector<std::vector<int>> band_faces(std::size_t(std::max(bands, 0)));
    std::vector<std::array<int, 4>> box(corners.size());  // x0, x1, y0, y1 (texel indices, inclusive)
    for (int f : faces) {
        const auto& c = corners[std::size_t(f)];
        const double lx = std::min({c[0].x(), c[1].x(), c[2].x()}), hx = std::max({c[0].x(), c[1].x(), c[2].x()});
        const double ly = std::min({c[0].y(), c[1].y(), c[2].y()}), hy = std::max({c[0].y(), c[1].y(), c[2].y()});
        // Texel x's centre x + 0.5 lies in [lx, hx] for x in [ceil(lx - 0.5), floor(hx - 0.5)].
        const int x0 = std::max(0, int(std::ceil(lx - 0.5))), x1 = std::min(grid.width - 1, int(std::floor(hx - 0.5)));
        const int y0 = std::max(0, int(std::ceil(ly - 0.5))), y1 = std::min(grid.height - 1, int(std::floor(hy - 0.5)));
        if (x0 > x1 || y0 > y1) continue;
        box[std::size_t(f)] = {x0, x1, y0, y1};
        for (int b = y0 / kBand; b <= y1 / kBand; ++b) band_faces[std::size_t(b)].push_back(f);
    }
    std::atomic<int> rows{0};
    tbb::parallel_for(0, bands, [&](int b) {
        const int r0 = b * kBand, r1 = std::min(grid.height, r0 + kBand) - 1;
        for (int f : band_faces[std::size_t(b)]) {
            std::array<Vec2, 3> c = corners[std::size_t(f)];
            if (orientation_2d(c[0], c[1], c[2]) < 0) std::swap(c[1], c[2]);  // counter-clockwise
            const auto& bx = box[std::size_t(f)];
            for (int y = std::max(r0, bx[2]); y <= std::min(r1, bx[3]); ++y)
                for (int x = bx[0]; x <= bx[1]; ++x) {
                    const Vec2 q(x + 0.5, y + 0.5);
                    const int o0 = orientation_2d(c[0], c[1], q);
                    if (o0 < 0) continue;
                    const int o1 = orientation_2d(c[1], c[2], q);
                    if (o1 < 0) continue;
                    const int o2 = orientation_2d(c[2], c[0], q);
                    if (o2 < 0) continue;
                    visit(f, x, y, o0 > 0 && o1 > 0 && o2 > 0 ? TexelClaim::interior : TexelClaim::edge);
                }
        }
        if (row_done) row_done(rows += r1 - r0 + 1);
    });
}

long long pad_texels(int width, int height, int padding, std::vector<std::uint8_t>& rgba, const std::vector<std::uint8_t>& covered) {
    std::vector<std::uint8_t> filled(covered.begin(), covered.end());
    std::vector<std::uint8_t> next;
    long long added = 0;
    for (int pass = 0; pass < padding; ++pass) {
        next = filled;
        std::atomic<long long> pass_added{0};
        tbb::parallel_for(0, height, [&](int y) {
            long long row_added = 0;
            for (int x = 0; x < width; ++x) {
                const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
                if (filled[i]) continue;
                int sum[4] = {0, 0, 0, 0}, n = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const int xx = x + dx, yy = y + dy;
                        if ((dx == 0 && dy == 0) || xx < 0 || yy < 0 || xx >= width || yy >= height) continue;
                        const std::size_t j = std::size_t(yy) * std::size_t(width) + std::size_t(xx);
                        if (!filled[j]) continue;
                        for (int c = 0; c < 4; ++c) sum[c] += rgba[4 * j + std::size_t(c)];
                        ++n;
                    }
                if (n == 0) continue;
                for (int c = 0; c < 4; ++c) rgba[4 * i + std::size_t(c)] = std::uint8_t((sum[c] + n / 2) / n);
                next[i] = 1;
                ++row_added;
            }
            pass_added += row_added;
        });
        // A texel filled in this pass is read by its neighbours only in the next one: `filled`
        // is this pass's start, and rgba of a texel not filled at the start is never read.
        filled.swap(next);
        added += pass_added;
        if (pass_added == 0) break;
    }
    return added;
}

}  // namespace ctmap

#include "ctmap/refine/segment_grid.h"

#include <algorithm>

namespace ctmap {

SegmentGrid::SegmentGrid(double cell, const std::vector<Vec2>& uv, const std::vector<std::array<int, 2>>& edges)
    : cell_(cell), uv_(uv), edges_(edges), stamp_(edges.size(), 0), big_flag_(edges.size(), 0) {
    for (int e = 0; e < int(edges.size()); ++e) insert(e);
}

void SegmentGrid::insert(int e) {
    const Vec2 &a = uv_[edges_[e][0]], &b = uv_[edges_[e][1]];
    if (!small(a, b)) {
        big_flag_[e] = 1;
        big_.push_back(e);
        return;
    }
    big_flag_[e] = 0;
    for_cells(a, b, [&](std::uint64_t key) { cells_[key].push_back(e); });
}

void SegmentGrid::remove(int e) {
    if (big_flag_[e]) {
        big_.erase(std::find(big_.begin(), big_.end(), e));
        return;
    }
    for_cells(uv_[edges_[e][0]], uv_[edges_[e][1]], [&](std::uint64_t key) {
        auto& v = cells_[key];
        v.erase(std::find(v.begin(), v.end(), e));
    });
}

bool SegmentGrid::small(const Vec2& a, const Vec2& b) const {
    const double x0 = std::min(a.x(), b.x()) / cell_, x1 = std::max(a.x(), b.x()) / cell_;
    const double y0 = std::min(a.y(), b.y()) / cell_, y1 = std::max(a.y(), b.y()) / cell_;
    if (!(std::abs(x0) < kMaxIndex && std::abs(x1) < kMaxIndex && std::abs(y0) < kMaxIndex &&
          std::abs(y1) < kMaxIndex))
        return false;  // also false for NaN
    return (std::floor(x1) - std::floor(x0) + 1) * (std::floor(y1) - std::floor(y0) + 1) <= kMaxCells;
}

std::int64_t SegmentGrid::cell_index(double c) const { return std::int64_t(std::floor(c / cell_)); }

}  // namespace ctmap

#pragma once
/// \file segment_grid.h
/// A uniform grid of moving segments (the UV border edges during the paper's relaxation, §2.4):
/// the border edges a moved vertex's edges may meet, found in O(1) on average.
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// Uniform grid of the UV border edges, updated as border vertices move, so that checking a
/// moved vertex's two border edges costs O(1) on average instead of O(border). An edge whose box
/// covers too many cells (it grew long, or the map is far from where the grid was sized) goes to
/// a list that every query scans; a query that large scans every edge. So the grid stays correct
/// and bounded whatever the map does.
class SegmentGrid {
public:
    /// \param cell the cells' side; `uv` and `edges` are kept by reference and must outlive the grid.
    SegmentGrid(double cell, const std::vector<Vec2>& uv, const std::vector<std::array<int, 2>>& edges);
    /// Files edge e under the cells its box covers (or the list of big edges).
    void insert(int e);
    /// Takes edge e out. \pre the edge's ends are where they were when it was inserted.
    void remove(int e);
    /// Calls f(edge) once for every edge that may meet the box of [a, b] (and maybe others).
    template <class F>
    void query(const Vec2& a, const Vec2& b, F&& f) {
        if (!small(a, b)) {
            for (int e = 0; e < int(edges_.size()); ++e) f(e);
            return;
        }
        ++tick_;
        auto visit = [&](int e) {
            if (stamp_[e] != tick_) {
                stamp_[e] = tick_;
                f(e);
            }
        };
        for (int e : big_) visit(e);
        for_cells(a, b, [&](std::uint64_t key) {
            auto it = cells_.find(key);
            if (it == cells_.end()) return;
            for (int e : it->second) visit(e);
        });
    }

private:
    static constexpr double kMaxCells = 64;
    static constexpr double kMaxIndex = 1e9;  // cell indices must fit in 32 bits

    bool small(const Vec2& a, const Vec2& b) const;
    template <class F>
    void for_cells(const Vec2& a, const Vec2& b, F&& f) {
        const std::int64_t x0 = cell_index(std::min(a.x(), b.x())), x1 = cell_index(std::max(a.x(), b.x()));
        const std::int64_t y0 = cell_index(std::min(a.y(), b.y())), y1 = cell_index(std::max(a.y(), b.y()));
        for (std::int64_t x = x0; x <= x1; ++x)
            for (std::int64_t y = y0; y <= y1; ++y)
                f((std::uint64_t(std::uint32_t(std::int32_t(x))) << 32) | std::uint32_t(std::int32_t(y)));
    }
    std::int64_t cell_index(double c) const;

    double cell_;
    const std::vector<Vec2>& uv_;
    const std::vector<std::array<int, 2>>& edges_;
    std::unordered_map<std::uint64_t, std::vector<int>> cells_;
    std::vector<unsigned> stamp_;
    std::vector<char> big_flag_;
    std::vector<int> big_;
    unsigned tick_ = 0;
};

}  // namespace ctmap

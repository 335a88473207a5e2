#include "ctmap/refine/border_guard.h"

#include "ctmap/certify/certificate.h"

namespace ctmap {

BorderGuard::BorderGuard(const std::vector<int>& loop, const Vec2& lo, const Vec2& hi) : loop_(loop), lo_(lo), hi_(hi) {
    const std::size_t n = loop.size();
    for (std::size_t i = 0; i < n; ++i) edges_.push_back({loop[i], loop[(i + 1) % n]});
}

bool BorderGuard::inside(const std::vector<Vec2>& uv) const {
    for (int v : loop_) {
        const Vec2& p = uv[v];
        if (!(p.x() >= lo_.x() && p.x() <= hi_.x() && p.y() >= lo_.y() && p.y() <= hi_.y())) return false;
    }
    return true;
}

bool BorderGuard::ok(const std::vector<Vec2>& uv) const {
    return inside(uv) && (edges_.size() < 3 || count_border_crossings(uv, edges_) == 0);
}

std::vector<int> BorderGuard::crossing_vertices(const std::vector<Vec2>& uv) const {
    std::vector<std::array<int, 2>> pairs;
    if (edges_.size() >= 3) count_border_crossings(uv, edges_, &pairs);
    std::vector<int> out;
    for (const auto& p : pairs)
        for (int e : p) out.insert(out.end(), {edges_[e][0], edges_[e][1]});
    return out;
}

}  // namespace ctmap

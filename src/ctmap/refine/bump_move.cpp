#include "ctmap/refine/bump_move.h"

#include <cmath>
#include <limits>

namespace ctmap {

namespace {

/// One bump: `uv[vertex]` moves by `d`, everything within r of it by d * (1 - s^2)^2.
/// \return false if r < 3.1 |d| or a UV would leave [lo, hi] (uv then partly moved).
bool bump_once(std::vector<Vec2>& uv, int vertex, const Vec2& d, double r, const Vec2& lo, const Vec2& hi) {
    if (!(r >= 3.1 * d.norm())) return false;
    const Vec2 p = uv[vertex];
    for (Vec2& q : uv) {
        const double s = (q - p).norm() / r;
        if (s >= 1) continue;
        const double w = (1 - s * s) * (1 - s * s);
        q += w * d;
        if (!(q.x() >= lo.x() && q.y() >= lo.y() && q.x() <= hi.x() && q.y() <= hi.y())) return false;
    }
    return true;
}

}  // namespace

bool bump_move(std::vector<Vec2>& uv, int vertex, const Vec2& target, const std::vector<int>& fixed, const Vec2& lo,
               const Vec2& hi, int max_steps, double max_radius) {
    if (!(target - uv[vertex]).allFinite()) return false;
    if (target == uv[vertex]) return true;
    std::vector<Vec2> out = uv;
    // A move longer than the bump allows is split into equal steps, each a bump of its own (the
    // composition of diffeomorphisms is one); the reach is measured again before each.
    for (int step = 0;; ++step) {
        const Vec2 p = out[vertex];
        double r = std::numeric_limits<double>::infinity();
        for (int f : fixed)
            if (f != vertex) r = std::min(r, (out[f] - p).norm());
        r = std::min(r, max_radius);
        if (!std::isfinite(r) || !(r > 0)) return false;
        const Vec2 rest = target - p;
        const int steps = int(std::ceil(3.1 * rest.norm() / r));
        if (steps > max_steps - step) return false;
        if (steps <= 1) {
            if (!bump_once(out, vertex, rest, r, lo, hi)) return false;
            break;
        }
        if (!bump_once(out, vertex, rest / steps, r, lo, hi)) return false;
    }
    out[vertex] = target;
    uv = std::move(out);
    return true;
}

}  // namespace ctmap

#include "ctmap/refine/flip_free_step.h"

#include <tbb/parallel_reduce.h>
#include <tbb/blocked_range.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace ctmap {

double smallest_positive_root(double a, double b, double c) {
    const double inf = std::numeric_limits<double>::infinity();
    // Relative to the terms' size, a vanishing a makes the quadratic linear.
    const double scale = std::abs(a) + std::abs(b) + std::abs(c);
    if (!(scale > 0)) return inf;
    if (std::abs(a) <= 1e-14 * scale) return b < 0 ? -c / b : inf;
    const double disc = b * b - 4 * a * c;
    if (disc < 0) return inf;
    // The stable form: q = -(b + sign(b) sqrt(disc)) / 2, roots q / a and c / q.
    const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
    double t = inf;
    if (q != 0) {
        const double r1 = q / a, r2 = c / q;
        if (r1 > 0) t = std::min(t, r1);
        if (r2 > 0) t = std::min(t, r2);
    }
    return t;
}

double max_flip_free_step(const std::vector<Tri>& faces, const std::vector<Vec2>& uv, const std::vector<Vec2>& d,
                          int sigma, bool parallel) {
    const double inf = std::numeric_limits<double>::infinity();
    auto cross = [](const Vec2& p, const Vec2& q) { return p.x() * q.y() - p.y() * q.x(); };
    auto face_step = [&](const Tri& t) {
        const Vec2 q1 = uv[t[1]] - uv[t[0]], q2 = uv[t[2]] - uv[t[0]];
        const Vec2 r1 = d[t[1]] - d[t[0]], r2 = d[t[2]] - d[t[0]];
        const double c = sigma * cross(q1, q2);
        const double b = sigma * (cross(q1, r2) + cross(r1, q2));
        const double a = sigma * cross(r1, r2);
        return smallest_positive_root(a, b, c);
    };
    if (!parallel) {
        double t = inf;
        for (const Tri& f : faces) t = std::min(t, face_step(f));
        return t;
    }
    // min is exact and associative: the same answer with any split.
    return tbb::parallel_reduce(
        tbb::blocked_range<std::size_t>(0, faces.size(), 4096), inf,
        [&](const tbb::blocked_range<std::size_t>& r, double t) {
            for (std::size_t f = r.begin(); f != r.end(); ++f) t = std::min(t, face_step(faces[f]));
            return t;
        },
        [](double x, double y) { return std::min(x, y); });
}

}  // namespace ctmap

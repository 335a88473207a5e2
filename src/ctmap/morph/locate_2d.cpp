#include "ctmap/morph/locate_2d.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ctmap/certify/certificate.h"

namespace ctmap {
namespace {

/// The point of segment ab nearest to p, as the parameter along ab.
double segment_parameter(const Vec2& p, const Vec2& a, const Vec2& b) {
    const double l = (b - a).squaredNorm();
    return l > 0 ? std::clamp((p - a).dot(b - a) / l, 0.0, 1.0) : 0.0;
}

/// Barycentric coordinates of p in (a, b, c), in floating point, clamped to [0, 1] and summing to 1.
Vec3 barycentric(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c) {
    auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
    const double area = cross(b - a, c - a);
    Vec3 l(cross(b - p, c - p) / area, cross(c - p, a - p) / area, cross(a - p, b - p) / area);
    l = l.cwiseMax(0.0);
    const double s = l.sum();
    return s > 0 ? Vec3(l / s) : Vec3(1.0 / 3, 1.0 / 3, 1.0 / 3);
}

/// The number of grid cells along a side of `cells` cells' length, clamped in double (NaN: 1).
int cell_count(double cells) { return cells >= 1 ? int(std::min(std::ceil(cells), 4096.0)) : 1; }

/// The cell (of `n`, each `size` long) holding offset `d`, clamped in double (NaN: 0).
int cell_of(double d, double size, int n) {
    const double c = std::floor(d / size);
    return c >= 0 ? int(std::min(c, double(n - 1))) : 0;
}

}  // namespace

TriangleLocator::TriangleLocator(const std::vector<Vec2>& uv, const std::vector<Tri>& faces) : uv_(uv), faces_(faces) {
    Eigen::AlignedBox2d box;
    for (const Tri& t : faces)
        for (int v : t) box.extend(uv[v]);
    if (box.isEmpty()) box.extend(Vec2(0, 0));
    // About two triangles per cell; square cells.
    const Vec2 size = box.sizes().cwiseMax(1e-300);
    const double cells = std::max(1.0, 0.5 * double(faces.size()));
    const double side = std::sqrt(size.x() * size.y() / cells);
    nx_ = cell_count(size.x() / side);
    ny_ = cell_count(size.y() / side);
    lo_ = box.min();
    cell_ = Vec2(size.x() / nx_, size.y() / ny_);
    std::vector<int> count(std::size_t(nx_) * ny_ + 1, 0);
    auto range = [&](const Tri& t, int& i0, int& i1, int& j0, int& j1) {
        Eigen::AlignedBox2d b;
        for (int v : t) b.extend(uv[v]);
        i0 = cell_of(b.min().x() - lo_.x(), cell_.x(), nx_);
        i1 = cell_of(b.max().x() - lo_.x(), cell_.x(), nx_);
        j0 = cell_of(b.min().y() - lo_.y(), cell_.y(), ny_);
        j1 = cell_of(b.max().y() - lo_.y(), cell_.y(), ny_);
    };
    for (const Tri& t : faces) {
        int i0, i1, j0, j1;
        range(t, i0, i1, j0, j1);
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) ++count[cell_index(i, j) + 1];
    }
    for (std::size_t k = 1; k < count.size(); ++k) count[k] += count[k - 1];
    start_ = count;
    items_.resize(std::size_t(start_.back()));
    for (int f = 0; f < int(faces.size()); ++f) {
        int i0, i1, j0, j1;
        range(faces[f], i0, i1, j0, j1);
        for (int j = j0; j <= j1; ++j)
            for (int i = i0; i <= i1; ++i) items_[std::size_t(count[cell_index(i, j)]++)] = f;
    }
}

Location TriangleLocator::locate(const Vec2& p) const {
    Location out;
    if (faces_.empty()) return out;
    const int ci = cell_of(p.x() - lo_.x(), cell_.x(), nx_);
    const int cj = cell_of(p.y() - lo_.y(), cell_.y(), ny_);
    const int c = cell_index(ci, cj);
    for (int k = start_[c]; k < start_[c + 1]; ++k) {
        const Tri& t = faces_[items_[k]];
        const Vec2 &a = uv_[t[0]], &b = uv_[t[1]], &d = uv_[t[2]];
        const int s = orientation_2d(a, b, d);
        if (orientation_2d(a, b, p) * s < 0 || orientation_2d(b, d, p) * s < 0 || orientation_2d(d, a, p) * s < 0)
            continue;
        out.face = items_[k];
        for (int q = 0; q < 3; ++q)
            if (uv_[t[q]] == p) {
                out.corner = q;
                out.bary = Vec3::Unit(q);
                return out;
            }
        out.bary = barycentric(p, a, b, d);
        return out;
    }
    // Outside every triangle: rounding at the border. The nearest triangle, searched ring by ring
    // until a ring lies farther than the best distance found.
    out.inside = false;
    double best = std::numeric_limits<double>::max();
    for (int r = 0; r <= std::max(nx_, ny_); ++r) {
        if (out.face >= 0 && (r - 1) * std::min(cell_.x(), cell_.y()) > std::sqrt(best)) break;
        for (int j = cj - r; j <= cj + r; ++j)
            for (int i = ci - r; i <= ci + r; ++i) {
                if (i < 0 || j < 0 || i >= nx_ || j >= ny_ || (std::abs(i - ci) != r && std::abs(j - cj) != r)) continue;
                const int cc = cell_index(i, j);
                for (int k = start_[cc]; k < start_[cc + 1]; ++k) {
                    const Tri& t = faces_[items_[k]];
                    for (int e = 0; e < 3; ++e) {
                        const Vec2 &a = uv_[t[e]], &b = uv_[t[(e + 1) % 3]];
                        const double s = segment_parameter(p, a, b);
                        const double d = (a + s * (b - a) - p).squaredNorm();
                        if (d < best) {
                            best = d;
                            out.face = items_[k];
                            out.bary = Vec3::Zero();
                            out.bary[e] = 1 - s;
                            out.bary[(e + 1) % 3] = s;
                        }
                    }
                }
            }
    }
    return out;
}

}  // namespace ctmap

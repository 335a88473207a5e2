#pragma once
// Random feasible feature sets (issue 3, must-show 1): the image points are the images of mesh
// vertices under a known one-to-one map of the disc — Tutte's embedding onto the unit circle,
// then a twist whose angle grows towards the centre — so a valid constrained map always exists.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <random>

#include "ctmap/cut/work_mesh.h"
#include "ctmap/domain/starter_features.h"
#include "ctmap/map_texture.h"
#include "ctmap/mesh.h"

namespace ctmap::test {

using ctmap::tutte_map;  // domain/starter_features.h

/// A twist of the unit disc: angle += strength (1 - r^2). One-to-one, the identity on the circle.
inline Vec2 twist(const Vec2& p, double strength) {
    const double r = p.norm(), a = std::atan2(p.y(), p.x()) + strength * (1 - r * r);
    return Vec2(r * std::cos(a), r * std::sin(a));
}

/// Whether q lies inside `polygon` (non-zero winding) and at least `margin` from its sides: the
/// input rule for an interior feature of a chart whose border polygon this is.
inline bool clear_inside(const std::vector<Vec2>& polygon, const Vec2& q, double margin = 1e-3) {
    int winding = 0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Vec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()], ab = b - a;
        const double t = std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        if ((a + t * ab - q).norm() < margin) return false;
        const double cross = ab.x() * (q.y() - a.y()) - ab.y() * (q.x() - a.x());
        if (a.y() <= q.y() && b.y() > q.y() && cross > 0) ++winding;
        if (a.y() > q.y() && b.y() <= q.y() && cross < 0) --winding;
    }
    return winding != 0;
}

/// One random feature set of a sweep: `features` on `mesh` (from data/meshes), twisted by `twist`,
/// drawn from `seed` (random_features with 8 border features).
struct RandomSetCase {
    const char* mesh;
    int features;
    double twist;
    std::uint32_t seed;
};

struct RandomFeatures {
    std::vector<int> vertex;  ///< feature vertices
    std::vector<Vec2> uv;     ///< their image points (UV, in [0,1]^2)
};

/// Picks `n_border` border features and up to `n_total - n_border` interior ones, image points
/// from `tutte` twisted by `strength`; interior features are kept only clear of the border
/// polygon (the input rule "interior features inside the border polygon") unless
/// `anywhere_inside_the_disc` (issue 12: the automatic border must hold them).
inline RandomFeatures random_features(const TriMesh& mesh, const std::vector<Vec2>& tutte, int n_total, int n_border,
                                      double strength, std::mt19937& rng, bool mirror = false,
                                      bool anywhere_inside_the_disc = false) {
    WorkMesh wm(mesh);
    std::vector<int> loop = wm.border_loop();
    RandomFeatures out;
    std::vector<char> used(mesh.num_vertices(), 0);
    for (int v : loop) used[v] = 1;  // border vertices only as chosen below
    std::shuffle(loop.begin(), loop.end(), rng);
    n_border = std::min<int>(n_border, int(loop.size()));
    std::vector<int> chosen(loop.begin(), loop.begin() + n_border);
    auto image = [&](int v) {
        Vec2 p = twist(tutte[v], strength);
        if (mirror) p.x() = -p.x();
        return Vec2(0.5 + 0.45 * p.x(), 0.5 + 0.45 * p.y());
    };
    // Border polygon in border order (for the inside test).
    std::vector<int> order = wm.border_loop();
    std::vector<Vec2> poly;
    for (int v : order)
        if (std::find(chosen.begin(), chosen.end(), v) != chosen.end()) poly.push_back(image(v));
    auto inside = [&](const Vec2& q) {
        // Distance to every edge at least `margin`, and winding number non-zero.
        const double margin = 1e-3;
        int wn = 0;
        for (std::size_t i = 0; i < poly.size(); ++i) {
            const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
            const Vec2 ab = b - a;
            const double t = std::clamp((q - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
            if ((a + t * ab - q).norm() < margin) return false;
            const double cross = ab.x() * (q.y() - a.y()) - ab.y() * (q.x() - a.x());
            if (a.y() <= q.y() && b.y() > q.y() && cross > 0) ++wn;
            if (a.y() > q.y() && b.y() <= q.y() && cross < 0) --wn;
        }
        return wn != 0;
    };
    for (int v : chosen) {
        out.vertex.push_back(v);
        out.uv.push_back(image(v));
    }
    std::vector<int> interior;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (!used[v]) interior.push_back(v);
    std::shuffle(interior.begin(), interior.end(), rng);
    for (int v : interior) {
        if (int(out.vertex.size()) >= n_total) break;
        const Vec2 q = image(v);
        if (!anywhere_inside_the_disc && !inside(q)) continue;
        out.vertex.push_back(v);
        out.uv.push_back(q);
    }
    return out;
}

/// The set as `map_texture` takes it: features named f0, f1, ... in order.
inline std::vector<MapFeature> map_features_of(const RandomFeatures& rf) {
    std::vector<MapFeature> out(rf.vertex.size());
    for (std::size_t i = 0; i < out.size(); ++i) {
        out[i].name = "f" + std::to_string(i);
        out[i].vertex = rf.vertex[i];
        out[i].uv = rf.uv[i];
    }
    return out;
}

/// `n` 3D point features inside random faces, imaged by the barycentric mix of `tutte` (one-to-one
/// on each face, so on the disc), after `border` border vertex features (all of them: the border
/// polygon is then Tutte's and holds every interior point). Issue 17's dense layouts
/// (bench/hard_layouts points, tests/test_cut_dense.cpp).
inline std::vector<MapFeature> point_features(const TriMesh& mesh, const std::vector<Vec2>& tutte, int n, int border,
                                              std::mt19937& rng) {
    std::vector<MapFeature> out = map_features_of(random_features(mesh, tutte, border, border, 0.0, rng));
    std::uniform_int_distribution<int> face(0, mesh.num_faces() - 1);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; int(out.size()) < border + n; ++i) {
        const Tri& t = mesh.faces[face(rng)];
        // Uniform in the triangle, kept 2% of the way clear of its sides.
        const double r1 = std::sqrt(u(rng)), r2 = u(rng);
        const double a = 1 - r1, b = r1 * (1 - r2), c = r1 * r2;
        if (std::min({a, b, c}) < 0.02) continue;
        MapFeature f;
        f.name = "p" + std::to_string(i);
        f.point = a * mesh.positions[t[0]] + b * mesh.positions[t[1]] + c * mesh.positions[t[2]];
        const Vec2 q = a * tutte[t[0]] + b * tutte[t[1]] + c * tutte[t[2]];
        f.uv = Vec2(0.5 + 0.45 * q.x(), 0.5 + 0.45 * q.y());
        out.push_back(f);
    }
    return out;
}

/// The benchmarks' random feasible set (bench/scaling_row, bench/isometric_row): `n` features,
/// a quarter of them (3 to 40) on the border, twisted by `strength`, from `seed`.
inline std::vector<MapFeature> bench_features(const TriMesh& mesh, int n, double strength, unsigned seed) {
    std::mt19937 rng(seed);
    const int border = std::max(3, std::min(40, n / 4));
    return map_features_of(random_features(mesh, tutte_map(mesh), n, border, strength, rng));
}

}  // namespace ctmap::test

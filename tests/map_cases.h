#pragma once
// Cut meshes built by hand (no call to the cut) for the embedding, relaxation and certificate
// tests: a disc with three border features (one patch = the whole mesh), a planar grid cut along
// a straight row of edges into two patches, a triangulated triangle, a helical strip.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>
#include <set>

#include "ctmap/cut/cut_mesh.h"
#include "ctmap/mesh.h"

namespace ctmap::test {

/// The border loop of a disc, in the faces' orientation (the interior on the left).
inline std::vector<int> border_loop_by_sets(const TriMesh& m) {
    std::set<std::pair<int, int>> directed;
    for (const Tri& t : m.faces)
        for (int k = 0; k < 3; ++k) directed.insert({t[k], t[(k + 1) % 3]});
    std::map<int, int> next;
    for (const auto& [a, b] : directed)
        if (!directed.count({b, a})) next[a] = b;
    std::vector<int> loop;
    if (next.empty()) return loop;
    const int start = next.begin()->first;
    int v = start;
    do {
        loop.push_back(v);
        v = next.at(v);
    } while (v != start && loop.size() <= next.size());
    return loop;
}

/// A cut mesh and the UVs of its features.
struct CutCase {
    TriMesh input;
    CutMesh cut;
    std::vector<Vec2> feature_uv;
};

/// Input vertices: any incident face, barycentric coordinates a unit vector.
inline void fill_vertex_faces(CutCase& c) {
    const TriMesh& m = c.input;
    c.cut.vertex_face.assign(m.num_vertices(), -1);
    c.cut.vertex_bary.assign(m.num_vertices(), Vec3::Zero());
    for (int f = 0; f < m.num_faces(); ++f)
        for (int k = 0; k < 3; ++k) {
            const int v = m.faces[f][k];
            if (c.cut.vertex_face[v] >= 0) continue;
            c.cut.vertex_face[v] = f;
            c.cut.vertex_bary[v] = Vec3::Unit(k);
        }
}

/// A disc with three features on its border at thirds of the border loop: one patch, the whole
/// mesh; its sides are the border arcs between the features.
inline CutCase disc_case(const TriMesh& mesh, std::array<Vec2, 3> uv = {Vec2(0.1, 0.1), Vec2(0.9, 0.2),
                                                                         Vec2(0.35, 0.85)}) {
    CutCase c;
    c.input = mesh;
    c.cut.mesh = mesh;
    c.cut.num_input_vertices = mesh.num_vertices();
    const std::vector<int> loop = border_loop_by_sets(mesh);
    const int n = int(loop.size());
    const std::array<int, 3> at{0, n / 3, (2 * n) / 3};
    c.cut.feature_vertex = {loop[at[0]], loop[at[1]], loop[at[2]]};
    c.cut.face_patch.assign(mesh.faces.size(), 0);
    Patch p;
    p.corners = {0, 1, 2};
    for (int k = 0; k < 3; ++k) {
        const int end = k == 2 ? n : at[k + 1];
        for (int i = at[k]; i <= end; ++i) p.sides[k].push_back(loop[i % n]);
    }
    c.cut.patches = {p};
    c.feature_uv = {uv[0], uv[1], uv[2]};
    fill_vertex_faces(c);
    return c;
}

/// A grid on [0, 1]^2 with nx x ny cells, z = bump * sin(pi x) sin(pi y) (0: planar). Diagonals
/// alternate, so that each corner cell of the square has a triangle with two border edges
/// (its third edge joins two border vertices: a flat edge once the border is a side).
inline TriMesh grid_mesh(int nx, int ny, double bump = 0) {
    TriMesh m;
    const double pi = std::acos(-1.0);
    for (int j = 0; j <= ny; ++j)
        for (int i = 0; i <= nx; ++i) {
            const double x = double(i) / nx, y = double(j) / ny;
            m.positions.emplace_back(x, y, bump * std::sin(pi * x) * std::sin(pi * y));
        }
    auto id = [&](int i, int j) { return j * (nx + 1) + i; };
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
            if ((i + j) % 2) {
                m.faces.push_back({a, b, c});
                m.faces.push_back({a, c, d});
            } else {
                m.faces.push_back({a, b, d});
                m.faces.push_back({b, c, d});
            }
        }
    return m;
}

/// The grid (nx, ny even) cut along the row y = 1/2 into two patches. Features: 0 = L (left
/// middle), 1 = B (bottom middle), 2 = R (right middle), 3 = T (top middle); image triangles
/// (L, B, R) below the cut and (L, R, T) above it, sharing the side L-R (the cut).
inline CutCase grid_two_patches(int nx, int ny, double bump = 0.2) {
    CutCase c;
    c.input = grid_mesh(nx, ny, bump);
    c.cut.mesh = c.input;
    c.cut.num_input_vertices = c.input.num_vertices();
    auto id = [&](int i, int j) { return j * (nx + 1) + i; };
    const int h = ny / 2, mx = nx / 2;
    c.cut.feature_vertex = {id(0, h), id(mx, 0), id(nx, h), id(mx, ny)};
    c.feature_uv = {Vec2(0.03, 0.47), Vec2(0.55, 0.02), Vec2(0.96, 0.53), Vec2(0.41, 0.97)};
    for (const Tri& t : c.input.faces) {
        double y = 0;
        for (int v : t) y += c.input.positions[v].y();
        c.cut.face_patch.push_back(y / 3 < 0.5 ? 0 : 1);
    }
    Patch lo, hi;
    lo.corners = {0, 1, 2};
    hi.corners = {0, 2, 3};
    for (int j = h; j >= 0; --j) lo.sides[0].push_back(id(0, j));  // L down the left border
    for (int i = 1; i <= mx; ++i) lo.sides[0].push_back(id(i, 0));  // ... along the bottom to B
    for (int i = mx; i <= nx; ++i) lo.sides[1].push_back(id(i, 0));  // B to the right corner
    for (int j = 1; j <= h; ++j) lo.sides[1].push_back(id(nx, j));  // ... up to R
    for (int i = nx; i >= 0; --i) lo.sides[2].push_back(id(i, h));  // R back along the cut to L
    for (int i = 0; i <= nx; ++i) hi.sides[0].push_back(id(i, h));  // L along the cut to R
    for (int j = h; j <= ny; ++j) hi.sides[1].push_back(id(nx, j));  // R up the right border
    for (int i = nx - 1; i >= mx; --i) hi.sides[1].push_back(id(i, ny));  // ... along the top to T
    for (int i = mx; i >= 0; --i) hi.sides[2].push_back(id(i, ny));  // T along the top
    for (int j = ny - 1; j >= h; --j) hi.sides[2].push_back(id(0, j));  // ... down to L
    c.cut.patches = {lo, hi};
    fill_vertex_faces(c);
    return c;
}

/// A triangle A, B, C in a tilted 3D plane, triangulated with N segments per side, every vertex
/// jittered within the plane (along its side for side vertices) by up to `jitter` of the spacing.
/// `param[v]` holds (s, t) with position = A + s (B - A) + t (C - A). One patch, corners at A, B, C.
inline CutCase planar_triangle(int N, double jitter, unsigned seed, std::vector<Vec2>* param) {
    const Vec3 A(0.2, -0.1, 0.3), B(1.7, 0.4, -0.2), C(0.5, 1.3, 0.9);
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> U(-jitter / N, jitter / N);
    CutCase c;
    TriMesh& m = c.input;
    std::map<std::pair<int, int>, int> id;
    param->clear();
    for (int j = 0; j <= N; ++j)
        for (int i = 0; i + j <= N; ++i) {
            double s = double(i) / N, t = double(j) / N;
            const bool corner = (i == 0 && j == 0) || i == N || j == N;
            if (!corner) {
                if (j == 0) s += U(rng);                      // on side A-B
                else if (i == 0) t += U(rng);                 // on side C-A
                else if (i + j == N) { const double d = U(rng); s += d; t -= d; }  // on side B-C
                else { s += U(rng); t += U(rng); }
            }
            id[{i, j}] = m.num_vertices();
            param->emplace_back(s, t);
            m.positions.push_back(A + s * (B - A) + t * (C - A));
        }
    for (int j = 0; j < N; ++j)
        for (int i = 0; i + j < N; ++i) {
            m.faces.push_back({id[{i, j}], id[{i + 1, j}], id[{i, j + 1}]});
            if (i + j + 1 < N) m.faces.push_back({id[{i + 1, j}], id[{i + 1, j + 1}], id[{i, j + 1}]});
        }
    c.cut.mesh = m;
    c.cut.num_input_vertices = m.num_vertices();
    c.cut.feature_vertex = {id[{0, 0}], id[{N, 0}], id[{0, N}]};
    c.cut.face_patch.assign(m.faces.size(), 0);
    Patch p;
    p.corners = {0, 1, 2};
    for (int i = 0; i <= N; ++i) p.sides[0].push_back(id[{i, 0}]);
    for (int j = 0; j <= N; ++j) p.sides[1].push_back(id[{N - j, j}]);
    for (int j = N; j >= 0; --j) p.sides[2].push_back(id[{0, j}]);
    c.cut.patches = {p};
    c.feature_uv = {Vec2(0.13, 0.07), Vec2(0.91, 0.31), Vec2(0.27, 0.88)};
    fill_vertex_faces(c);
    return c;
}

/// A strip of `rings` concentric rows and K + 1 columns winding `turn` radians around the z
/// axis, rising slowly (a split washer). Vertex (k, r) = k * rings + r. Its UVs `uv_turn`:
/// the same strip flat, turning uv_turn radians, centred at (0.5, 0.5).
inline TriMesh helix_strip(int K, int rings, double turn, double uv_turn, std::vector<Vec2>* uv) {
    TriMesh m;
    uv->clear();
    for (int k = 0; k <= K; ++k)
        for (int r = 0; r < rings; ++r) {
            const double rad = 1.0 + 0.25 * r, a = turn * k / K, b = uv_turn * k / K;
            m.positions.emplace_back(rad * std::cos(a), rad * std::sin(a), 0.05 * a);
            uv->emplace_back(0.5 + 0.3 * rad * std::cos(b), 0.5 + 0.3 * rad * std::sin(b));
        }
    for (int k = 0; k < K; ++k)
        for (int r = 0; r + 1 < rings; ++r) {
            const int a = k * rings + r, b = (k + 1) * rings + r, c = (k + 1) * rings + r + 1, d = k * rings + r + 1;
            m.faces.push_back({a, b, c});
            m.faces.push_back({a, c, d});
        }
    return m;
}

}  // namespace ctmap::test

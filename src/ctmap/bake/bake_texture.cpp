#include "ctmap/bake/bake_texture.h"

#include <Eigen/Dense>
#include <algorithm>
#include <atomic>
#include <cmath>
#include <memory>
#include <optional>

#include "ctmap/bake/photo_sampler.h"
#include "ctmap/bake/texel_raster.h"
#include "ctmap/certify/certificate.h"
#include "ctmap/errors.h"
#include "ctmap/input_faces.h"
#include "ctmap/surface_locator.h"
#include "ctmap/unit_box.h"

namespace ctmap {
namespace {

using Mat2 = Eigen::Matrix2d;

/// Twice the area of face `t` of `m`.
double twice_area(const TriMesh& m, const Tri& t) {
    const Vec3& a = m.positions[std::size_t(t[0])];
    return (m.positions[std::size_t(t[1])] - a).cross(m.positions[std::size_t(t[2])] - a).norm();
}

void require_uvs(const TexturedMesh& m, const std::string& name) {
    if (m.uvs.empty() || m.uv_faces.size() != m.mesh.faces.size())
        throw BadInput(name, "has no texture coordinates (the bake needs " +
                                 std::string(name == "map" ? "the map's UVs: a map ctmap wrote" : "ONTO's own UV layout") + ")");
    for (std::size_t i = 0; i < m.uvs.size(); ++i)
        if (!m.uvs[i].allFinite()) throw BadInput(name, "texture coordinate " + std::to_string(i + 1) + " is not finite");
}

/// The barycentric-plane coordinates (b1, b2) of `p` in the triangle (a, b, c): p's projection
/// onto the triangle's plane is a + b1 (b - a) + b2 (c - a).
Vec2 plane_coordinates(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
    const Vec3 e1 = b - a, e2 = c - a, d = p - a;
    Mat2 g;
    g << e1.dot(e1), e1.dot(e2), e1.dot(e2), e2.dot(e2);
    return g.inverse() * Vec2(e1.dot(d), e2.dot(d));
}

/// A piece of an ONTO face: a map face inside it, in the face's barycentric plane.
struct Piece {
    std::array<Vec2, 3> corner;  ///< counter-clockwise
    Mat2 to_uv;                  ///< the map's UV = uv0 + to_uv (b - corner[0])
    Vec2 uv0;
    double footprint = 1;        ///< photo pixels per texel
    int chart = 0;
    bool degenerate = false;     ///< zero area in the plane (rounding): holds no point of its own
};

/// Why `onto` is not the mesh `map` was computed from (empty: it is), with `input_face` filled
/// when the map carries none.
std::string same_mesh(const TexturedMesh& map, const TexturedMesh& onto, std::vector<int>& input_face) {
    const int n = onto.mesh.num_vertices();
    if (n > map.mesh.num_vertices()) return "ONTO has more vertices than the map";
    const double tol = 1e-6 * std::max(diagonal(onto.mesh), 1e-300);
    for (int v = 0; v < n; ++v)
        if ((onto.mesh.positions[std::size_t(v)] - map.mesh.positions[std::size_t(v)]).norm() > tol)
            return "ONTO's vertex " + std::to_string(v) + " is not the map's";
    input_face = map.input_face.size() == map.mesh.faces.size() ? map.input_face : input_faces_of(onto.mesh, map.mesh);
    std::vector<double> area(onto.mesh.faces.size(), 0.0);  // twice the areas
    for (std::size_t g = 0; g < map.mesh.faces.size(); ++g) {
        const int f = input_face[g];
        if (f < 0 || f >= onto.mesh.num_faces()) return "the map's face " + std::to_string(g) + " lies in no face of ONTO";
        const Tri& F = onto.mesh.faces[std::size_t(f)];
        for (int v : map.mesh.faces[g])
            if (v < n && std::find(F.begin(), F.end(), v) == F.end())
                return "the map's face " + std::to_string(g) + " is not inside ONTO's face " + std::to_string(f);
        area[std::size_t(f)] += twice_area(map.mesh, map.mesh.faces[g]);
    }
    std::vector<char> has_piece(onto.mesh.faces.size(), 0);
    for (int f : input_face) has_piece[std::size_t(f)] = 1;
    for (std::size_t f = 0; f < area.size(); ++f) {
        if (!has_piece[f]) return "ONTO's face " + std::to_string(f) + " holds no face of the map";
        const double a = twice_area(onto.mesh, onto.mesh.faces[f]);
        if (std::abs(area[f] - a) > 1e-4 * a + 1e-12 * tol * tol)  // (a GLB map holds 32-bit floats)
            return "the map's faces do not tile ONTO's face " + std::to_string(f);
    }
    return "";
}

}  // namespace

std::vector<int> udim_tiles(const TexturedMesh& onto) {
    require_uvs(onto, "onto");
    std::vector<int> tiles;
    for (std::size_t f = 0; f < onto.uv_faces.size(); ++f) {
        const auto& t = onto.uv_faces[f];
        Vec2 lo = onto.uvs[std::size_t(t[0])], hi = lo;
        for (int k = 1; k < 3; ++k) lo = lo.cwiseMin(onto.uvs[std::size_t(t[k])]), hi = hi.cwiseMax(onto.uvs[std::size_t(t[k])]);
        // The tile of the triangle's centre; every corner must be in it (its border included).
        const Vec2 mid = 0.5 * (lo + hi);
        const double tu = std::floor(mid.x()), tv = std::floor(mid.y());
        const std::string where = "face " + std::to_string(f + 1) + "'s UVs (" + std::to_string(lo.x()) + ", " +
                                  std::to_string(lo.y()) + ")-(" + std::to_string(hi.x()) + ", " + std::to_string(hi.y()) + ")";
        if (lo.x() < tu || hi.x() > tu + 1 || lo.y() < tv || hi.y() > tv + 1)
            throw BadInput("onto", where + " cross a UV tile border: UVs outside [0, 1] mean UDIM tiles, one tile per triangle");
        if (tu < 0 || tv < 0 || tu > 9 || tv > 99)
            throw BadInput("onto", where + " are outside [0, 1] and in no UDIM tile (u in [0, 10], v >= 0)");
        tiles.push_back(1001 + int(tu) + 10 * int(tv));
    }
    std::sort(tiles.begin(), tiles.end());
    tiles.erase(std::unique(tiles.begin(), tiles.end()), tiles.end());
    return tiles;
}

BakeResult bake_texture(const TexturedMesh& map, const std::vector<Image>& photos, const TexturedMesh& onto,
                        const BakeOptions& options) {
    require_uvs(map, "map");
    require_uvs(onto, "onto");
    if (photos.empty()) throw BadInput("map", "no photo to bake");
    int charts = 1;
    for (int c : map.chart) charts = std::max(charts, c + 1);
    if (photos.size() != 1 && int(photos.size()) < charts)
        throw BadInput("map", "has " + std::to_string(charts) + " charts but " + std::to_string(photos.size()) + " photos");
    std::vector<std::unique_ptr<PhotoSampler>> samplers;
    for (const Image& p : photos) samplers.push_back(std::make_unique<PhotoSampler>(p));
    auto chart_of = [&](std::size_t g) { return photos.size() == 1 || map.chart.size() != map.mesh.faces.size() ? 0 : map.chart[g]; };

    TexelGrid grid;
    grid.width = options.width > 0 ? options.width : photos.front().width;
    grid.height = options.height > 0 ? options.height : photos.front().height;
    grid.tile = options.tile;
    if (double(grid.width) * double(grid.height) > double(1 << 28))
        throw BadInput("", "a texture of " + std::to_string(grid.width) + " x " + std::to_string(grid.height) +
                               " texels is larger than 2^28 texels");

    // ONTO's faces in the tile, their UV triangles in texel coordinates.
    const int nf = onto.mesh.num_faces();
    std::vector<std::array<Vec2, 3>> texel(static_cast<std::size_t>(nf));
    std::vector<int> faces;
    for (int f = 0; f < nf; ++f) {
        const auto& t = onto.uv_faces[std::size_t(f)];
        std::array<Vec2, 3> uv;
        bool inside = true;
        for (int k = 0; k < 3; ++k) {
            uv[std::size_t(k)] = onto.uvs[std::size_t(t[std::size_t(k)])];
            const Vec2 d = uv[std::size_t(k)] - grid.tile;
            inside = inside && d.x() >= 0 && d.x() <= 1 && d.y() >= 0 && d.y() <= 1;
            texel[std::size_t(f)][std::size_t(k)] = grid.texel_of(uv[std::size_t(k)]);
        }
        if (!inside) continue;
        if (orientation_2d(uv[0], uv[1], uv[2]) == 0)
            throw BadInput("onto", "face " + std::to_string(f + 1) + " has a degenerate UV triangle (zero area)");
        // A sliver that rounding makes flat in texel coordinates holds no texel centre: left out.
        const auto& t3 = texel[std::size_t(f)];
        if (orientation_2d(t3[0], t3[1], t3[2]) == 0) continue;
        faces.push_back(f);
    }

    BakeResult out;
    BakeStats& st = out.stats;
    st.faces = int(faces.size());
    std::vector<int> input_face;
    if (options.transfer != BakeTransfer::closest) {
        st.not_exact = same_mesh(map, onto, input_face);
        st.exact = st.not_exact.empty();
        if (!st.exact && options.transfer == BakeTransfer::exact)
            throw BadInput("onto", "is not the mesh the map was computed from (" + st.not_exact + "), so the transfer cannot be exact");
    } else {
        st.not_exact = "the closest transfer was asked for";
    }

    // Per ONTO face: texel coordinates -> its barycentric plane (b1, b2).
    std::vector<Mat2> to_plane(static_cast<std::size_t>(nf), Mat2::Zero());
    for (int f : faces) {
        const auto& c = texel[std::size_t(f)];
        Mat2 e;
        e.col(0) = c[1] - c[0], e.col(1) = c[2] - c[0];
        to_plane[std::size_t(f)] = e.inverse();
    }
    faces.erase(std::remove_if(faces.begin(), faces.end(), [&](int f) { return !to_plane[std::size_t(f)].allFinite(); }),
                faces.end());
    st.faces = int(faces.size());
    auto plane_point = [&](int f, double x, double y) {
        return Vec2(to_plane[std::size_t(f)] * (Vec2(x, y) - texel[std::size_t(f)][0]));
    };

    // Exact: each ONTO face's pieces.
    std::vector<int> first(std::size_t(nf) + 1, 0);
    std::vector<Piece> pieces;
    if (st.exact) {
        for (int f : input_face) ++first[std::size_t(f) + 1];
        for (int f = 0; f < nf; ++f) first[std::size_t(f) + 1] += first[std::size_t(f)];
        pieces.resize(map.mesh.faces.size());
        std::vector<int> fill(first.begin(), first.end() - 1);
        for (std::size_t g = 0; g < map.mesh.faces.size(); ++g) {
            const int f = input_face[g];
            const Tri& F = onto.mesh.faces[std::size_t(f)];
            const Vec3 &A = onto.mesh.positions[std::size_t(F[0])], &B = onto.mesh.positions[std::size_t(F[1])],
                       &C = onto.mesh.positions[std::size_t(F[2])];
            Piece p;
            std::array<Vec2, 3> uv;
            for (int k = 0; k < 3; ++k) {
                const int v = map.mesh.faces[g][std::size_t(k)];
                // ONTO's own corners exactly; the points the cut inserted by projection.
                Vec2 b = v == F[0] ? Vec2(0, 0) : v == F[1] ? Vec2(1, 0) : v == F[2] ? Vec2(0, 1)
                                                : plane_coordinates(A, B, C, map.mesh.positions[std::size_t(v)]);
                p.corner[std::size_t(k)] = b;
                uv[std::size_t(k)] = map.uvs[std::size_t(map.uv_faces[g][std::size_t(k)])];
            }
            if (orientation_2d(p.corner[0], p.corner[1], p.corner[2]) < 0) std::swap(p.corner[1], p.corner[2]), std::swap(uv[1], uv[2]);
            Mat2 e, u;
            e.col(0) = p.corner[1] - p.corner[0], e.col(1) = p.corner[2] - p.corner[0];
            u.col(0) = uv[1] - uv[0], u.col(1) = uv[2] - uv[0];
            p.to_uv = u * e.inverse();
            p.uv0 = uv[0];
            p.chart = chart_of(g);
            p.degenerate = orientation_2d(p.corner[0], p.corner[1], p.corner[2]) == 0 || !p.to_uv.allFinite();
            if (!p.to_uv.allFinite()) p.to_uv.setZero();
            const PhotoSampler& s = *samplers[std::size_t(p.chart)];
            const Mat2 j = Eigen::DiagonalMatrix<double, 2>(s.width(), s.height()) * p.to_uv * to_plane[std::size_t(f)];
            p.footprint = std::max(j.col(0).norm(), j.col(1).norm());
            pieces[std::size_t(fill[std::size_t(f)]++)] = p;
        }
    }

    // Closest: the map's surface, and per map face how many photo pixels a unit of surface spans.
    std::optional<SurfaceLocator> locator;
    std::vector<double> photo_scale, texel_scale;
    if (!st.exact) {
        try {
            locator.emplace(map.mesh);
        } catch (const BadInput&) {
            throw BadInput("map", "has no face of nonzero area: no surface to bake from");
        }
        st.max_distance = options.max_distance >= 0 ? options.max_distance : 0.01 * diagonal(onto.mesh);
        photo_scale.resize(map.mesh.faces.size());
        for (std::size_t g = 0; g < map.mesh.faces.size(); ++g) {
            const Tri& t = map.mesh.faces[g];
            const PhotoSampler& s = *samplers[std::size_t(chart_of(g))];
            const double a3 = twice_area(map.mesh, t);
            const auto& ut = map.uv_faces[g];
            Mat2 u;
            u.col(0) = (map.uvs[std::size_t(ut[1])] - map.uvs[std::size_t(ut[0])]).cwiseProduct(Vec2(s.width(), s.height()));
            u.col(1) = (map.uvs[std::size_t(ut[2])] - map.uvs[std::size_t(ut[0])]).cwiseProduct(Vec2(s.width(), s.height()));
            photo_scale[g] = a3 > 0 ? std::sqrt(std::abs(u.determinant()) / a3) : 0;
        }
        texel_scale.resize(std::size_t(nf));
        for (int f : faces) {
            const Tri& t = onto.mesh.faces[std::size_t(f)];
            const double a3 = twice_area(onto.mesh, t);
            texel_scale[std::size_t(f)] = a3 > 0 ? std::sqrt(std::abs(1.0 / to_plane[std::size_t(f)].determinant()) / a3) : 0;
        }
    }

    const std::size_t texels = std::size_t(grid.width) * std::size_t(grid.height);
    out.texture.width = grid.width, out.texture.height = grid.height, out.texture.channels = 4;
    out.texture.pixels.assign(texels * 4, 0);
    std::vector<std::uint8_t> claim(texels, 0);
    std::atomic<long long> twice{0}, far{0};
    auto put = [&](std::size_t i, const std::array<float, 4>& c) {
        for (std::size_t k = 0; k < 4; ++k) out.texture.pixels[4 * i + k] = std::uint8_t(std::lround(std::clamp(c[k], 0.0f, 255.0f)));
    };
    const int total_rows = grid.height;
    raster_texels(
        grid, texel, faces,
        [&](int f, int x, int y, TexelClaim how) {
            const std::size_t i = std::size_t(y) * std::size_t(grid.width) + std::size_t(x);
            const auto level = std::uint8_t(how);
            if (level < claim[i]) return;  // a corner or edge of a later face does not take a texel inside an earlier one
            if (level == std::uint8_t(TexelClaim::interior) && claim[i] == level) ++twice;
            const Vec2 b = plane_point(f, x + 0.5, y + 0.5);
            if (st.exact) {
                const int lo = first[std::size_t(f)], hi = first[std::size_t(f) + 1];
                if (hi == lo || !b.allFinite()) return;  // (same_mesh gives every face a piece)
                int best = lo;
                if (hi - lo > 1) {
                    best = -1;
                    double best_margin = -1e300;
                    for (int k = lo; k < hi && best < 0; ++k) {
                        const Piece& p = pieces[std::size_t(k)];
                        const auto& c = p.corner;
                        if (!p.degenerate && orientation_2d(c[0], c[1], b) >= 0 && orientation_2d(c[1], c[2], b) >= 0 &&
                            orientation_2d(c[2], c[0], b) >= 0)
                            best = k;
                    }
                    if (best < 0) {  // in a rounding gap at the face's border: the nearest piece
                        best = lo;
                        bool best_flat = true;
                        for (int k = lo; k < hi; ++k) {
                            const auto& c = pieces[std::size_t(k)].corner;
                            const bool flat = pieces[std::size_t(k)].degenerate;
                            double margin = 1e300;
                            for (int e = 0; e < 3; ++e) {
                                const Vec2 d = c[std::size_t((e + 1) % 3)] - c[std::size_t(e)];
                                const Vec2 r = b - c[std::size_t(e)];
                                margin = std::min(margin, (d.x() * r.y() - d.y() * r.x()) / std::max(d.norm(), 1e-300));
                            }
                            // A flat piece only when every piece is flat, else the one nearest.
                            if ((best_flat && !flat) || (flat == best_flat && margin > best_margin))
                                best_margin = margin, best = k, best_flat = flat;
                        }
                    }
                }
                const Piece& p = pieces[std::size_t(best)];
                const Vec2 uv = p.uv0 + p.to_uv * (b - p.corner[0]);
                put(i, samplers[std::size_t(p.chart)]->sample(uv, p.footprint));
            } else {
                const Tri& F = onto.mesh.faces[std::size_t(f)];
                const Vec3& A = onto.mesh.positions[std::size_t(F[0])];
                const Vec3 P = A + b.x() * (onto.mesh.positions[std::size_t(F[1])] - A) + b.y() * (onto.mesh.positions[std::size_t(F[2])] - A);
                const SurfacePoint hit = locator->closest(P);
                if (std::sqrt(hit.squared_distance) > st.max_distance) {
                    ++far;
                    return;
                }
                const Tri& G = map.mesh.faces[std::size_t(hit.face)];
                const Vec2 q = plane_coordinates(map.mesh.positions[std::size_t(G[0])], map.mesh.positions[std::size_t(G[1])],
                                                 map.mesh.positions[std::size_t(G[2])], hit.point);
                const auto& ut = map.uv_faces[std::size_t(hit.face)];
                const Vec2& u0 = map.uvs[std::size_t(ut[0])];
                const Vec2 uv = u0 + q.x() * (map.uvs[std::size_t(ut[1])] - u0) + q.y() * (map.uvs[std::size_t(ut[2])] - u0);
                const double ts = texel_scale[std::size_t(f)];
                const double footprint = ts > 0 ? photo_scale[std::size_t(hit.face)] / ts : 1;
                put(i, samplers[std::size_t(chart_of(std::size_t(hit.face)))]->sample(uv, footprint));
            }
            claim[i] = level;
        },
        [&](int rows) {
            if (options.progress) options.progress(rows, total_rows);
        });
    st.written_twice = twice;
    st.too_far = far;
    out.covered.resize(texels);
    for (std::size_t i = 0; i < texels; ++i) out.covered[i] = claim[i] != 0;
    st.covered = std::count(out.covered.begin(), out.covered.end(), std::uint8_t(1));
    st.padded = pad_texels(grid.width, grid.height, options.padding, out.texture.pixels, out.covered);
    return out;
}

}  // namespace ctmap

// `ctmap bake` (issue 42): the photo, aligned by a map's features, baked into another UV layout of
// the mesh. The oracles are independent of the bake's code: a layout whose vertices sit on texel
// centres, so the texel of an input vertex must hold the photo's colour at that vertex's ctmap UV
// (the map's vertex i is the input's, DESIGN §3), read with the test's own bilinear filter; and the
// same bake onto a subdivided copy (the same surface, the closest-point transfer) must agree with
// the exact one.
#include <algorithm>
#include <cmath>
#include <iostream>

#include "ctmap/bake/bake_texture.h"
#include "ctmap/certify/certificate.h"
#include "ctmap/io/features.h"
#include "ctmap/io/image.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "ctmap/subdivide.h"
#include "bake_cases.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

constexpr int kPhoto = 512;  // astronaut.png

/// The photo's colour at `uv` (OBJ's convention, pixel centres at half integers), bilinear,
/// clamped at the edge: the test's own reading, not the bake's sampler.
std::array<double, 4> photo_at(const Image& im, const Vec2& uv) {
    const double px = uv.x() * im.width - 0.5, py = (1 - uv.y()) * im.height - 0.5;
    const double fx = std::floor(px), fy = std::floor(py), tx = px - fx, ty = py - fy;
    auto at = [&](double x, double y, int c) {
        const int xi = int(std::clamp(x, 0.0, double(im.width - 1))), yi = int(std::clamp(y, 0.0, double(im.height - 1)));
        return double(im.pixels[(std::size_t(yi) * std::size_t(im.width) + std::size_t(xi)) * 4 + std::size_t(c)]);
    };
    std::array<double, 4> out{};
    for (int c = 0; c < 4; ++c)
        out[std::size_t(c)] = (1 - ty) * ((1 - tx) * at(fx, fy, c) + tx * at(fx + 1, fy, c)) +
                              ty * ((1 - tx) * at(fx, fy + 1, c) + tx * at(fx + 1, fy + 1, c));
    return out;
}

struct Nefertiti {
    TriMesh mesh;
    Image photo;
    std::vector<MapFeature> features;
    MapResult map;
};

const Nefertiti& nefertiti() {
    static const Nefertiti n = [] {
        Nefertiti x;
        x.mesh = read_mesh(data("meshes/nefertiti.off"));
        x.photo = read_image(data("images/astronaut.png"));
        FeatureSet fs = read_features(data("features/nefertiti_astronaut.json"));
        resolve_units(fs, kPhoto, kPhoto);
        x.features = map_features(fs, kPhoto, kPhoto);
        x.map = map_texture(x.mesh, x.features);
        return x;
    }();
    return n;
}

/// ONTO: the mesh with a planar layout, each vertex's UV on a texel centre of a `size`² texture.
TexturedMesh planar_layout(const TriMesh& mesh, int size) { return TexturedMesh::with_vertex_uvs(mesh, planar_uvs(mesh, size)); }

std::array<int, 2> texel_of(const Vec2& uv, int size) {
    return {int(std::floor(uv.x() * size)), int(std::floor((1 - uv.y()) * size))};
}

TEST(Bake, MapRecordsTheInputFaceEachFaceLiesIn) {
    // Every face of the map lies in its recorded input face: its corners' barycentric
    // coordinates there are in [0, 1] and they lie in its plane (to rounding).
    const Nefertiti& n = nefertiti();
    const TriMesh& m = n.map.cut.mesh;
    ASSERT_EQ(n.map.input_face.size(), m.faces.size());
    double worst_bary = 0, worst_plane = 0;
    for (std::size_t g = 0; g < m.faces.size(); ++g) {
        const Tri& F = n.mesh.faces[std::size_t(n.map.input_face[g])];
        const Vec3 &a = n.mesh.positions[std::size_t(F[0])], &b = n.mesh.positions[std::size_t(F[1])],
                   &c = n.mesh.positions[std::size_t(F[2])];
        const Vec3 normal = (b - a).cross(c - a);
        for (int v : m.faces[g]) {
            const Vec3& p = m.positions[std::size_t(v)];
            worst_plane = std::max(worst_plane, std::abs(normal.normalized().dot(p - a)));
            const double area = normal.norm();
            const double l0 = (c - b).cross(p - b).dot(normal) / (area * area), l1 = (a - c).cross(p - c).dot(normal) / (area * area);
            worst_bary = std::max({worst_bary, -l0, -l1, -(1 - l0 - l1)});
        }
    }
    EXPECT_LT(worst_bary, 1e-9);
    EXPECT_LT(worst_plane, 1e-9);
    // And it is written and read back with the map (OBJ).
    TempDir dir;
    write_obj(n.map.textured(), (dir / "map.obj"));
    EXPECT_EQ(read_textured_obj((dir / "map.obj")).input_face, n.map.input_face);
}

TEST(Bake, SameMeshIsExactAtEveryVertexAndFeature) {
    // Must-show 1: baked onto the mesh itself with another layout, every input vertex's texel
    // holds the photo's colour at the vertex's ctmap UV, and every feature's texel the photo's
    // colour at the feature's pixel: within 1/255 after rounding.
    const Nefertiti& n = nefertiti();
    // 4096²: the bake magnifies the 512² photo at every vertex (no mip level; at 2048² two border
    // vertices' pieces are stretched enough for the trilinear filter to blend in level 1).
    constexpr int size = 4096;
    const TexturedMesh onto = planar_layout(n.mesh, size);
    for (const Tri& t : onto.mesh.faces)
        ASSERT_NE(orientation_2d(onto.uvs[std::size_t(t[0])], onto.uvs[std::size_t(t[1])], onto.uvs[std::size_t(t[2])]), 0)
            << "the snapped layout has a degenerate triangle (the test's input)";
    BakeOptions opt;
    opt.width = opt.height = size;
    const BakeResult r = bake_texture(n.map.textured(), {n.photo}, onto, opt);
    ASSERT_TRUE(r.stats.exact) << r.stats.not_exact;
    EXPECT_EQ(r.stats.written_twice, 0);
    int worst = 0, checked = 0;
    auto baked = [&](const Vec2& uv, int c) {
        const auto [x, y] = texel_of(uv, size);
        return int(r.texture.pixels[(std::size_t(y) * size + std::size_t(x)) * 4 + std::size_t(c)]);
    };
    for (int v = 0; v < n.mesh.num_vertices(); ++v) {
        const auto [x, y] = texel_of(onto.uvs[std::size_t(v)], size);
        ASSERT_TRUE(r.covered[std::size_t(y) * size + std::size_t(x)]) << "vertex " << v << "'s texel is not covered";
        const auto want = photo_at(n.photo, n.map.uv[std::size_t(v)]);
        for (int c = 0; c < 4; ++c) worst = std::max(worst, std::abs(baked(onto.uvs[std::size_t(v)], c) - int(std::lround(want[std::size_t(c)]))));
        ++checked;
    }
    EXPECT_LE(worst, 1) << "over " << checked << " vertices";
    int worst_feature = 0;
    for (std::size_t i = 0; i < n.features.size(); ++i) {
        const int v = n.map.cut.feature_vertex[i];
        ASSERT_LT(v, n.mesh.num_vertices()) << "a vertex feature";
        const Vec2 pixel(n.features[i].uv.x() * kPhoto, (1 - n.features[i].uv.y()) * kPhoto);
        const auto want = photo_at(n.photo, image_to_uv(pixel, kPhoto, kPhoto));
        for (int c = 0; c < 4; ++c)
            worst_feature = std::max(worst_feature, std::abs(baked(onto.uvs[std::size_t(v)], c) - int(std::lround(want[std::size_t(c)]))));
    }
    EXPECT_LE(worst_feature, 1) << "over " << n.features.size() << " features";
    std::cout << "nefertiti onto itself (planar layout, " << size << "²): " << r.stats.covered << " texels, worst "
              << worst << "/255 over " << checked << " vertices, " << worst_feature << "/255 over "
              << n.features.size() << " features\n";
}

TEST(Bake, SubdividedCopyAgreesWithTheExactBake) {
    // Must-show 2: onto a subdivided copy (another tessellation of the same surface, the same
    // layout): the closest-point transfer, its mean colour difference over the covered texels
    // at most 2/255 against the exact bake onto the mesh itself.
    const Nefertiti& n = nefertiti();
    constexpr int size = 1024;
    const TexturedMesh onto = planar_layout(n.mesh, size);
    TriMesh uv_mesh;  // the layout as a flat mesh, subdivided like the surface
    for (const Vec2& t : onto.uvs) uv_mesh.positions.emplace_back(t.x(), t.y(), 0);
    uv_mesh.faces = onto.mesh.faces;
    const TriMesh fine = subdivide_midpoint(n.mesh, 1), fine_uv = subdivide_midpoint(uv_mesh, 1);
    std::vector<Vec2> uv;
    for (const Vec3& p : fine_uv.positions) uv.emplace_back(p.x(), p.y());
    const TexturedMesh fine_onto = TexturedMesh::with_vertex_uvs(fine, uv);
    BakeOptions opt;
    opt.width = opt.height = size;
    opt.padding = 0;
    const BakeResult exact = bake_texture(n.map.textured(), {n.photo}, onto, opt);
    const BakeResult closest = bake_texture(n.map.textured(), {n.photo}, fine_onto, opt);
    ASSERT_TRUE(exact.stats.exact);
    ASSERT_FALSE(closest.stats.exact);
    EXPECT_EQ(closest.stats.too_far, 0);
    double sum = 0;
    long long both = 0, only_one = 0;
    for (std::size_t i = 0; i < exact.covered.size(); ++i) {
        if (exact.covered[i] != closest.covered[i]) ++only_one;
        if (!exact.covered[i] || !closest.covered[i]) continue;
        for (int c = 0; c < 3; ++c) sum += std::abs(int(exact.texture.pixels[4 * i + std::size_t(c)]) - int(closest.texture.pixels[4 * i + std::size_t(c)]));
        ++both;
    }
    const double mean = sum / (3.0 * double(both));
    EXPECT_LE(mean, 2.0);
    EXPECT_LT(double(only_one), 1e-3 * double(both)) << "the same layout covers the same texels";
    std::cout << "subdivided copy (" << fine.num_faces() << " faces, closest point) vs the exact bake: mean "
              << mean << "/255 over " << both << " texels, " << only_one << " covered by one only\n";
}

TEST(Bake, OverlappingIslandsAreCountedAndTheLaterFaceWins) {
    // Two UV triangles on the same place: the texels strictly inside both are counted, and hold
    // the later face's colour. The map: a square in two triangles, its photo left half red,
    // right half blue; ONTO: the same square, its second triangle's UVs laid over the first's.
    TriMesh sq;
    sq.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)};
    sq.faces = {Tri{0, 1, 2}, Tri{0, 2, 3}};
    const TexturedMesh map = TexturedMesh::with_vertex_uvs(sq, {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)});
    Image photo;
    photo.width = photo.height = 64, photo.channels = 4;
    photo.pixels.assign(64 * 64 * 4, 255);
    for (int y = 0; y < 64; ++y)
        for (int x = 0; x < 64; ++x) {
            std::uint8_t* p = &photo.pixels[(std::size_t(y) * 64 + std::size_t(x)) * 4];
            p[0] = x < 32 ? 255 : 0, p[1] = 0, p[2] = x < 32 ? 0 : 255;
        }
    TexturedMesh onto = map;
    onto.uvs = {Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 0), Vec2(1, 0), Vec2(1, 1)};
    onto.uv_faces = {Tri{0, 1, 2}, Tri{3, 4, 5}};  // face 1 (the upper-left triangle in 3D) laid on face 0's UVs
    BakeOptions opt;
    opt.padding = 0;
    const BakeResult r = bake_texture(map, {photo}, onto, opt);
    EXPECT_GT(r.stats.written_twice, 64 * 64 / 2 - 2 * 64);
    EXPECT_LE(r.stats.written_twice, 64 * 64 / 2);
    // The oracle at texel (40, 50), in both UV triangles: face 1's point there, by its
    // barycentric coordinates in face 1's UV triangle (0,0), (1,0), (1,1).
    const int x = 40, y = 50;
    const Vec2 uv((x + 0.5) / 64, 1 - (y + 0.5) / 64);
    const double l2 = uv.y(), l1 = uv.x() - uv.y(), l0 = 1 - uv.x();
    const Vec3 p = l0 * sq.positions[0] + l1 * sq.positions[2] + l2 * sq.positions[3];  // face 1 = (0, 2, 3)
    const auto want = photo_at(photo, Vec2(p.x(), p.y()));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(r.texture.pixels[(std::size_t(y) * 64 + std::size_t(x)) * 4 + std::size_t(c)], want[std::size_t(c)], 1.0);
}

TEST(Bake, PaddingGrowsIslandsAndKeepsTheRestEmpty) {
    const Nefertiti& n = nefertiti();
    const TexturedMesh onto = planar_layout(n.mesh, 256);
    BakeOptions opt;
    opt.width = opt.height = 256;
    opt.padding = 4;
    const BakeResult r = bake_texture(n.map.textured(), {n.photo}, onto, opt);
    long long opaque = 0;
    for (std::size_t i = 0; i < r.covered.size(); ++i) {
        const std::uint8_t a = r.texture.pixels[4 * i + 3];
        if (r.covered[i]) EXPECT_EQ(a, 255);
        opaque += a != 0;
    }
    EXPECT_EQ(opaque, r.stats.covered + r.stats.padded);
    EXPECT_GT(r.stats.padded, 0);
    // Nothing farther than 4 texels (8-neighbour steps) from a covered texel is written.
    for (int y = 0; y < 256; ++y)
        for (int x = 0; x < 256; ++x) {
            if (r.texture.pixels[(std::size_t(y) * 256 + std::size_t(x)) * 4 + 3] == 0) continue;
            bool near = false;
            for (int dy = -4; dy <= 4 && !near; ++dy)
                for (int dx = -4; dx <= 4 && !near; ++dx) {
                    const int xx = x + dx, yy = y + dy;
                    near = xx >= 0 && yy >= 0 && xx < 256 && yy < 256 && r.covered[std::size_t(yy) * 256 + std::size_t(xx)];
                }
            ASSERT_TRUE(near) << "texel " << x << ", " << y;
        }
}

TEST(Bake, UdimTilesAreFoundPerTriangle) {
    TriMesh m;
    m.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
    m.faces = {Tri{0, 1, 2}, Tri{1, 3, 2}};
    TexturedMesh t = TexturedMesh::with_vertex_uvs(m, {});
    t.uvs = {Vec2(0.1, 0.1), Vec2(0.9, 0.1), Vec2(0.1, 0.9), Vec2(1.1, 1.1), Vec2(1.9, 1.1), Vec2(1.1, 1.9)};
    t.uv_faces = {Tri{0, 1, 2}, Tri{3, 4, 5}};
    EXPECT_EQ(udim_tiles(t), (std::vector<int>{1001, 1012}));
    t.uvs[4] = Vec2(2.5, 1.1);  // across the border of tiles 1012 and 1013
    EXPECT_THROW(udim_tiles(t), BadInput);
    t.uvs[4] = Vec2(1.9, 1.1), t.uvs[3] = Vec2(-0.5, 1.1), t.uvs[5] = Vec2(-0.5, 1.9), t.uvs[4] = Vec2(-0.1, 1.5);
    EXPECT_THROW(udim_tiles(t), BadInput);  // left of u = 0: no UDIM number
}

}  // namespace
}  // namespace ctmap::test

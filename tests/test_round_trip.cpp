// OBJ and GLB round trips (issue 2, point 4): a mesh with per-corner UVs written and read back.
// OBJ is text written with the shortest decimal form that reads back to the same double, so
// positions and UVs must come back bitwise. GLB stores 32-bit floats, with v flipped: positions
// must come back as exactly float(original), UVs as exactly the float of what was written.
// scripts/test.sh runs these again under the sanitizers (`ctest -R RoundTrip`).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <set>

#include "ctmap/io/glb_io.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

std::uint64_t bits(double x) { return std::bit_cast<std::uint64_t>(x); }
std::uint32_t bits(float x) { return std::bit_cast<std::uint32_t>(x); }

/// Values that trip up decimal printing and parsing.
std::vector<double> awkward_values() {
    const double denorm_min = std::numeric_limits<double>::denorm_min();
    const double norm_min = std::numeric_limits<double>::min();
    return {0.0,
            -0.0,
            0.1,
            0.2,
            0.3,
            1.0 / 3.0,
            2.0 / 3.0,
            1e-17,
            denorm_min,                          // 4.9e-324, the smallest denormal
            3 * denorm_min,
            norm_min,                            // 2.2250738585072014e-308
            std::nextafter(norm_min, 0.0),       // the largest denormal
            std::nextafter(1.0, 0.0),            // 1 - 2^-53
            1.0 - 1e-12,
            1.0 - 1e-7,
            0.9999999,
            1.0,
            std::nextafter(1.0, 2.0),
            0.5,
            123456789.123456789,
            -987.654321e-5,
            std::numeric_limits<double>::max(),
            std::numeric_limits<double>::lowest(),
            9007199254740993.0,                  // 2^53 + 1 (rounds to 2^53)
            5e-324 * 7};
}

/// A grid of n x n vertices, two triangles per cell, each corner with its own UV (so every
/// vertex carries several UVs, as at a seam); positions and UVs drawn from `values`.
TexturedMesh grid_with_corner_uvs(int n, const std::vector<double>& pos_values, const std::vector<double>& uv_values,
                                  unsigned seed) {
    std::mt19937 g(seed);
    auto pick = [&](const std::vector<double>& v) { return v[g() % v.size()]; };
    TexturedMesh tm;
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) tm.mesh.positions.emplace_back(pick(pos_values), pick(pos_values), pick(pos_values));
    for (int j = 0; j + 1 < n; ++j)
        for (int i = 0; i + 1 < n; ++i) {
            const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
            tm.mesh.faces.push_back({a, b, d});
            tm.mesh.faces.push_back({a, d, c});
        }
    for (std::size_t f = 0; f < tm.mesh.faces.size(); ++f) {
        Tri t;
        for (int k = 0; k < 3; ++k) {
            t[k] = int(tm.uvs.size());
            tm.uvs.emplace_back(pick(uv_values), pick(uv_values));
        }
        tm.uv_faces.push_back(t);
    }
    tm.chart.assign(tm.mesh.faces.size(), 0);
    return tm;
}

/// Every finite double is as likely as any other bit pattern: denormals, huge, tiny, -0.
std::vector<double> random_doubles(std::size_t n, unsigned seed) {
    std::mt19937_64 g(seed);
    std::vector<double> out;
    while (out.size() < n) {
        const double x = std::bit_cast<double>(g());
        if (std::isfinite(x)) out.push_back(x);
    }
    return out;
}

std::vector<double> random_unit_doubles(std::size_t n, unsigned seed) {
    std::mt19937_64 g(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<double> out(n);
    for (double& x : out) x = u(g);
    return out;
}

/// Positions and UVs bitwise equal, faces and UV faces identical.
void expect_bitwise_equal(const TexturedMesh& a, const TexturedMesh& b) {
    ASSERT_EQ(a.mesh.positions.size(), b.mesh.positions.size());
    ASSERT_EQ(a.uvs.size(), b.uvs.size());
    int mismatches = 0;
    for (std::size_t i = 0; i < a.mesh.positions.size(); ++i)
        for (int c = 0; c < 3; ++c)
            if (bits(a.mesh.positions[i][c]) != bits(b.mesh.positions[i][c]) && ++mismatches <= 5)
                ADD_FAILURE() << "vertex " << i << " coordinate " << c << ": wrote " << a.mesh.positions[i][c]
                              << ", read " << b.mesh.positions[i][c];
    for (std::size_t i = 0; i < a.uvs.size(); ++i)
        for (int c = 0; c < 2; ++c)
            if (bits(a.uvs[i][c]) != bits(b.uvs[i][c]) && ++mismatches <= 5)
                ADD_FAILURE() << "uv " << i << " component " << c << ": wrote " << a.uvs[i][c] << ", read "
                              << b.uvs[i][c];
    EXPECT_EQ(mismatches, 0);
    EXPECT_EQ(std::memcmp(a.mesh.positions.data(), b.mesh.positions.data(), a.mesh.positions.size() * sizeof(Vec3)), 0);
    EXPECT_EQ(std::memcmp(a.uvs.data(), b.uvs.data(), a.uvs.size() * sizeof(Vec2)), 0);
    EXPECT_EQ(a.mesh.faces, b.mesh.faces);
    EXPECT_EQ(a.uv_faces, b.uv_faces);
}

std::string map_kd_line(const std::string& mtl) {
    const std::string text = read_file(mtl);
    const std::size_t at = text.find("map_Kd ");
    if (at == std::string::npos) return {};
    return text.substr(at + 7, text.find('\n', at) - at - 7);
}

TEST(RoundTrip, ObjKeepsAwkwardDoublesBitwise) {
    TempDir dir;
    const TexturedMesh tm = grid_with_corner_uvs(12, awkward_values(), awkward_values(), 1);
    const std::string image = data("images/astronaut.png");
    write_obj(tm, dir / "m.obj", image);
    std::string read_image_path;
    const TexturedMesh back = read_textured_obj(dir / "m.obj", &read_image_path);
    expect_bitwise_equal(tm, back);
    // The MTL names the image relative to the OBJ, and that resolves to the very same file.
    EXPECT_FALSE(map_kd_line(dir / "m.mtl").empty());
    EXPECT_NE(map_kd_line(dir / "m.mtl").front(), '/') << "map_Kd is written relative to the OBJ";
    EXPECT_TRUE(std::filesystem::equivalent(read_image_path, image)) << read_image_path << " vs " << image;
}

TEST(RoundTrip, ObjKeepsRandomBitPatternsBitwise) {
    TempDir dir;
    // Positions over the whole double range; UVs uniform in [0, 1) with full 53-bit mantissas.
    const TexturedMesh tm = grid_with_corner_uvs(40, random_doubles(4000, 2), random_unit_doubles(4000, 3), 4);
    write_obj(tm, dir / "m.obj");
    const TexturedMesh back = read_textured_obj(dir / "m.obj");
    expect_bitwise_equal(tm, back);
    // CGAL's reader (istream >> double) gets the same positions from the same file.
    const TriMesh cgal = read_mesh(dir / "m.obj");
    ASSERT_EQ(cgal.positions.size(), tm.mesh.positions.size());
    EXPECT_EQ(std::memcmp(cgal.positions.data(), tm.mesh.positions.data(), tm.mesh.positions.size() * sizeof(Vec3)), 0);
    EXPECT_EQ(cgal.faces, tm.mesh.faces);
}

TEST(RoundTrip, ObjKeepsPatchGroups) {
    TempDir dir;
    TexturedMesh tm = grid_with_corner_uvs(6, awkward_values(), awkward_values(), 1);
    for (std::size_t f = 0; f < tm.mesh.faces.size(); ++f) tm.patch.push_back(int(f * 7 % 5));  // runs and jumps
    write_obj(tm, dir / "m.obj");
    const TexturedMesh back = read_textured_obj(dir / "m.obj");
    expect_bitwise_equal(tm, back);
    EXPECT_EQ(back.patch, tm.patch);
    // Without groups on every face, no patch ids are made up.
    tm.patch.clear();
    write_obj(tm, dir / "n.obj");
    EXPECT_TRUE(read_textured_obj(dir / "n.obj").patch.empty());
}

TEST(RoundTrip, ObjMapKdFollowsTheImageBesideTheObj) {
    TempDir dir;
    std::filesystem::create_directories(dir / "tex");
    std::filesystem::copy_file(data("images/astronaut.png"), dir / "tex/face photo.png");
    const TexturedMesh tm = grid_with_corner_uvs(3, {0.0, 1.0, 2.0}, {0.25, 0.5}, 5);
    write_obj(tm, dir / "m.obj", dir / "tex/face photo.png");
    EXPECT_EQ(map_kd_line(dir / "m.mtl"), "tex/face photo.png");
    std::string image;
    read_textured_obj(dir / "m.obj", &image);
    EXPECT_EQ(image, dir / "tex/face photo.png");
    // No image: no map_Kd, and the reader reports none.
    write_obj(tm, dir / "plain.obj");
    EXPECT_EQ(map_kd_line(dir / "plain.mtl"), "");
    read_textured_obj(dir / "plain.obj", &image);
    EXPECT_EQ(image, "");
}

/// What a GLB holds for a UV component: float32, with v flipped (glTF's v runs downwards).
float glb_u(double u) { return float(u); }
float glb_v(double v) { return float(1.0 - v); }

TEST(RoundTrip, GlbKeepsFloatPositionsUvsAndTheEmbeddedPng) {
    TempDir dir;
    std::vector<double> uv_values = awkward_values();
    uv_values.erase(std::remove_if(uv_values.begin(), uv_values.end(), [](double x) { return x < 0 || x > 1; }),
                    uv_values.end());
    for (double x : random_unit_doubles(200, 6)) uv_values.push_back(x);
    std::vector<double> pos_values = random_unit_doubles(200, 7);
    for (double& x : pos_values) x = (x - 0.5) * 1e3;
    pos_values.insert(pos_values.end(), {0.1, 1.0 / 3.0, 1e-17, -0.0, 1e-310});
    const TexturedMesh tm = grid_with_corner_uvs(20, pos_values, uv_values, 8);
    const std::string image = data("images/astronaut.png");
    write_glb(tm, dir / "m.glb", image);

    GlbTexture tex;
    const TexturedMesh back = read_glb(dir / "m.glb", &tex);
    ASSERT_EQ(back.mesh.faces.size(), tm.mesh.faces.size());
    ASSERT_EQ(back.uv_faces.size(), tm.mesh.faces.size());
    // glTF has one UV per vertex, so vertices are split: one per distinct (vertex, uv) corner pair.
    std::set<std::pair<int, int>> pairs;
    for (std::size_t f = 0; f < tm.mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) pairs.emplace(tm.mesh.faces[f][k], tm.uv_faces[f][k]);
    EXPECT_EQ(back.mesh.positions.size(), pairs.size());
    for (int i = 0; i < tm.mesh.num_vertices(); ++i)  // the input order is kept (DESIGN §3)
        EXPECT_EQ(back.mesh.positions[i], tm.mesh.positions[i].cast<float>().cast<double>()) << "vertex " << i;

    int mismatches = 0;
    auto check = [&](bool ok, std::size_t f, int k, const char* what) {
        if (!ok && ++mismatches <= 5) ADD_FAILURE() << "face " << f << " corner " << k << ": " << what;
    };
    for (std::size_t f = 0; f < tm.mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const Vec3& p = tm.mesh.positions[tm.mesh.faces[f][k]];
            const Vec3& q = back.mesh.positions[back.mesh.faces[f][k]];
            for (int c = 0; c < 3; ++c) check(bits(float(p[c])) == bits(float(q[c])) && double(float(p[c])) == q[c], f, k, "position");
            const Vec2& uv = tm.uvs[tm.uv_faces[f][k]];
            const Vec2& r = back.uvs[back.uv_faces[f][k]];
            check(bits(float(r.x())) == bits(glb_u(uv.x())) && r.x() == double(glb_u(uv.x())), f, k, "u");
            // v is flipped back in double: exactly 1 - (the stored float) rounded once ...
            check(bits(r.y()) == bits(1.0 - double(glb_v(uv.y()))), f, k, "v (bitwise)");
            // ... which gives back the stored float itself whenever 1 - v is 0 or at least 2^-30
            // (then 1 - stored is exact in a double); below that it is within 2^-54.
            const float stored = glb_v(uv.y());
            if (stored == 0 || stored >= 0x1p-30f)
                check(bits(float(1.0 - r.y())) == bits(stored), f, k, "v (float(1 - v))");
            else
                check(std::abs((1.0 - r.y()) - double(stored)) <= 0x1p-54, f, k, "v (within 2^-54)");
        }
    EXPECT_EQ(mismatches, 0);

    // The texture is embedded: the PNG file's own bytes, as the base-colour texture.
    EXPECT_EQ(tex.mime_type, "image/png");
    const std::string png = read_file(image);
    ASSERT_EQ(tex.bytes.size(), png.size());
    EXPECT_EQ(std::memcmp(tex.bytes.data(), png.data(), png.size()), 0);
    // The whole file is one GLB: magic "glTF", version 2, and no external file beside it.
    const std::string glb = read_file(dir / "m.glb");
    ASSERT_GE(glb.size(), 12u);
    EXPECT_EQ(glb.substr(0, 4), "glTF");
    EXPECT_EQ(std::uint8_t(glb[4]), 2);
    EXPECT_EQ(dir.count(), 1);
}

TEST(RoundTrip, GlbWithoutImageHasNoTexture) {
    TempDir dir;
    const TexturedMesh tm = grid_with_corner_uvs(3, {0.0, 1.0, 2.0}, {0.25, 0.5}, 9);
    write_glb(tm, dir / "m.glb");
    GlbTexture tex;
    tex.mime_type = "stale";
    const TexturedMesh back = read_glb(dir / "m.glb", &tex);
    EXPECT_EQ(back.mesh.faces.size(), tm.mesh.faces.size());
    EXPECT_EQ(tex.mime_type, "");
    EXPECT_TRUE(tex.bytes.empty());
}

/// UVs for a real mesh: its positions projected on the xy plane, scaled into [0, 1]^2.
std::vector<Vec2> planar_uvs(const TriMesh& m) {
    Eigen::AlignedBox3d box;
    for (const Vec3& p : m.positions) box.extend(p);
    std::vector<Vec2> uvs;
    for (const Vec3& p : m.positions)
        uvs.emplace_back((p.x() - box.min().x()) / box.sizes().x(), (p.y() - box.min().y()) / box.sizes().y());
    return uvs;
}

TEST(RoundTrip, NefertitiOffToObjAndGlb) {
    TempDir dir;
    const std::string off = data("meshes/nefertiti.off");
    const TriMesh mesh = read_mesh(off);
    ASSERT_EQ(mesh.num_vertices(), 299);
    ASSERT_EQ(mesh.num_faces(), 562);
    const TexturedMesh tm = TexturedMesh::with_vertex_uvs(mesh, planar_uvs(mesh));

    write_obj(tm, dir / "n.obj", data("images/astronaut.png"));
    expect_bitwise_equal(tm, read_textured_obj(dir / "n.obj"));
    const TriMesh again = read_mesh(dir / "n.obj");  // and through CGAL, as `ctmap info` reads it
    EXPECT_EQ(std::memcmp(again.positions.data(), mesh.positions.data(), mesh.positions.size() * sizeof(Vec3)), 0);
    EXPECT_EQ(again.faces, mesh.faces);

    write_glb(tm, dir / "n.glb", data("images/astronaut.png"));
    const TexturedMesh g = read_glb(dir / "n.glb");
    ASSERT_EQ(g.mesh.faces.size(), mesh.faces.size());
    ASSERT_EQ(g.mesh.num_vertices(), mesh.num_vertices()) << "one UV per vertex: no vertex is split";
    for (int i = 0; i < mesh.num_vertices(); ++i) {  // the input order is kept (DESIGN §3)
        EXPECT_EQ(g.mesh.positions[i], mesh.positions[i].cast<float>().cast<double>()) << "vertex " << i;
        EXPECT_EQ(float(g.uvs[i].x()), float(tm.uvs[i].x())) << "vertex " << i;
    }
    EXPECT_EQ(g.mesh.faces, mesh.faces);
    for (std::size_t f = 0; f < mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const Vec3 p = mesh.positions[mesh.faces[f][k]];
            EXPECT_EQ(g.mesh.positions[g.mesh.faces[f][k]], p.cast<float>().cast<double>()) << f << "," << k;
        }
}

TEST(RoundTrip, CliConvertKeepsTheInputOrderAndPositions) {
    TempDir dir;
    const std::string off = data("meshes/nefertiti.off");
    const RunResult r = run_ctmap("convert " + q(off) + " -o " + q(dir / "n.obj"));
    ASSERT_EQ(r.code, 0) << r.out;
    const TriMesh mesh = read_mesh(off);
    const TexturedMesh back = read_textured_obj(dir / "n.obj");
    ASSERT_EQ(back.mesh.positions.size(), mesh.positions.size());
    EXPECT_EQ(std::memcmp(back.mesh.positions.data(), mesh.positions.data(), mesh.positions.size() * sizeof(Vec3)), 0);
    EXPECT_EQ(back.mesh.faces, mesh.faces);
    EXPECT_TRUE(back.uvs.empty());
}

}  // namespace
}  // namespace ctmap::test

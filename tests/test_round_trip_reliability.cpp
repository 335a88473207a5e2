// Issue 17, must-show 1, the good inputs that used to fail: a map must not depend on the unit the
// mesh was saved in, point features copied from float32 files or printed with 4 decimals land on
// their vertices, JPEG photographs are read upright (EXIF), and `check` and `render` read the GLB
// that `map` writes. Every map is certified by `ctmap check` from the written files.
// Named RoundTrip*, so scripts/test.sh runs them again under ASan + UBSan.
#include <stb/stb_image_write.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "ctmap/errors.h"
#include "ctmap/io/glb_io.h"
#include "ctmap/io/image.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

namespace fs = std::filesystem;

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

/// The "N vertices inserted" and "M faces" parts of a `map` report's summary line ("" if absent).
std::string insertion_summary(const std::string& report) {
    const std::size_t at = report.find(" vertices inserted");
    const std::size_t start = report.rfind(", ", at);
    const std::size_t faces = report.find(" faces", at);
    if (at == std::string::npos || start == std::string::npos || faces == std::string::npos) return "";
    const std::size_t count = report.rfind(' ', faces - 1) + 1;
    return report.substr(start + 2, at - start - 2) + " inserted, " + report.substr(count, faces - count) + " faces";
}

/// `mesh` as OFF with every double written exactly (17 digits).
std::string off_text(const TriMesh& mesh) {
    std::ostringstream os;
    os.precision(17);
    os << "OFF\n" << mesh.num_vertices() << " " << mesh.num_faces() << " 0\n";
    for (const Vec3& p : mesh.positions) os << p.x() << " " << p.y() << " " << p.z() << "\n";
    for (const Tri& t : mesh.faces) os << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
    return os.str();
}

/// Maps `mesh_file` with the shipped features, checks the written map, returns it.
TexturedMesh map_and_check(const TempDir& d, const std::string& mesh_file, const std::string& features,
                           const std::string& out, const std::string& extra = "") {
    const RunResult m = run_ctmap("map " + q(mesh_file) + " " + q(features) + " -o " + q(d / out) + " -q " + extra);
    EXPECT_EQ(m.code, 0) << m.out;
    const RunResult c = run_ctmap("check " + q(d / out) + " --features " + q(features));
    EXPECT_EQ(c.code, 0) << c.out;
    EXPECT_TRUE(has(c.out, ": valid")) << c.out;
    return m.code == 0 ? read_textured_obj(d / out) : TexturedMesh{};
}

TEST(RoundTripReliability, TheMapDoesNotDependOnTheMeshUnit) {
    TempDir d;
    const std::string features = data("features/nefertiti_astronaut.json");
    const TriMesh mesh = read_mesh(data("meshes/nefertiti.off"));
    const TexturedMesh reference = map_and_check(d, data("meshes/nefertiti.off"), features, "ref.obj");
    ASSERT_FALSE(reference.uvs.empty());
    // Before: 1e160 and 1e300 gave exit 3, 1e-300 hung in the path search (12 GB).
    for (const double scale : {1e-300, 1e-150, 1e160, 1e300}) {
        SCOPED_TRACE("scale " + std::to_string(std::log10(scale)));
        TriMesh scaled = mesh;
        for (Vec3& p : scaled.positions) p *= scale;
        write_file(d / "scaled.off", off_text(scaled));
        const TexturedMesh map = map_and_check(d, d / "scaled.off", features, "scaled.obj");
        ASSERT_EQ(map.uvs.size(), reference.uvs.size());
        double worst = 0;
        for (std::size_t i = 0; i < map.uvs.size(); ++i) worst = std::max(worst, (map.uvs[i] - reference.uvs[i]).norm());
        EXPECT_LT(worst, 1e-9) << "the UVs differ from the unscaled map's";
        // The input's own coordinates are written back, bitwise.
        for (int v = 0; v < mesh.num_vertices(); ++v) ASSERT_EQ(map.mesh.positions[v], scaled.positions[v]) << v;
    }
    // One vertex far away (y = 1e23) gave "relax: the map is not valid on entry".
    TriMesh outlier = mesh;
    outlier.positions[150].y() = 1e23;
    write_file(d / "outlier.off", off_text(outlier));
    map_and_check(d, d / "outlier.off", features, "outlier.obj");
}

/// nefertiti as binary float32 PLY and STL, and its features as 3D points at those float vertices,
/// printed with `digits` significant digits (0: every digit of the float; 4: 4 decimals).
struct FloatCase {
    std::string ply, stl, features;
};

FloatCase float_case(const TempDir& d, int digits) {
    const TriMesh mesh = read_mesh(data("meshes/nefertiti.off"));
    std::string ply = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(mesh.num_vertices()) +
                      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                      std::to_string(mesh.num_faces()) + "\nproperty list uchar int vertex_indices\nend_header\n";
    auto put = [](std::string& s, const auto& v) { s.append(reinterpret_cast<const char*>(&v), sizeof v); };
    for (const Vec3& p : mesh.positions)
        for (int k = 0; k < 3; ++k) put(ply, float(p[k]));
    for (const Tri& t : mesh.faces) {
        put(ply, std::uint8_t(3));
        for (int k = 0; k < 3; ++k) put(ply, std::int32_t(t[k]));
    }
    std::string stl(80, 'x');
    put(stl, std::uint32_t(mesh.num_faces()));
    for (const Tri& t : mesh.faces) {
        for (int k = 0; k < 3; ++k) put(stl, 0.0f);
        for (int c = 0; c < 3; ++c)
            for (int k = 0; k < 3; ++k) put(stl, float(mesh.positions[t[c]][k]));
        stl.append(2, '\0');
    }
    // The shipped features, each vertex given as its float point instead.
    std::string f = read_file(data("features/nefertiti_astronaut.json"));
    std::string out;
    std::size_t at = 0;
    for (std::size_t k; (k = f.find("\"vertex\": ", at)) != std::string::npos;) {
        const std::size_t end = f.find_first_not_of("0123456789", k + 10);
        const int v = std::stoi(f.substr(k + 10, end - k - 10));
        std::ostringstream os;
        os.precision(digits > 0 ? digits : 9);
        if (digits == 4) os << std::fixed;
        os << "\"point\": [" << double(float(mesh.positions[v].x())) << ", " << double(float(mesh.positions[v].y()))
           << ", " << double(float(mesh.positions[v].z())) << "]";
        out += f.substr(at, k - at) + os.str();
        at = end;
    }
    out += f.substr(at);
    const std::string tag = std::to_string(digits);
    write_file(d / ("m" + tag + ".ply"), ply);
    write_file(d / ("m" + tag + ".stl"), stl);
    write_file(d / ("f" + tag + ".json"), out);
    return {d / ("m" + tag + ".ply"), d / ("m" + tag + ".stl"), d / ("f" + tag + ".json")};
}

TEST(RoundTripReliability, PointFeaturesCopiedFromFloatFilesLandOnTheirVertices) {
    TempDir d;
    // The reference: the same features given as vertex indices on the OFF file.
    const RunResult ref = run_ctmap("map " + q(data("meshes/nefertiti.off")) + " " +
                                    q(data("features/nefertiti_astronaut.json")) + " -o " + q(d / "ref.obj"));
    ASSERT_EQ(ref.code, 0) << ref.out;
    const std::string expected = insertion_summary(ref.out);
    ASSERT_FALSE(expected.empty()) << ref.out;
    // Before: exit 3 ("internal failure") for points exactly at float32 vertices; and points
    // printed with 4 decimals were inserted beside their border vertices, off the border.
    for (const int digits : {0, 7, 4}) {
        SCOPED_TRACE(std::to_string(digits) + " digits");
        const FloatCase c = float_case(d, digits);
        for (const std::string& mesh : {c.ply, c.stl}) {
            const TexturedMesh map = map_and_check(d, mesh, c.features, "float.obj");
            // 16 features, every one on an input vertex: the same vertices inserted as with
            // vertex indices, nothing more (a point beside its vertex would add one and a patch).
            const RunResult r = run_ctmap("map " + q(mesh) + " " + q(c.features) + " -o " + q(d / "float.obj"));
            EXPECT_EQ(insertion_summary(r.out), expected) << r.out;
            if (digits == 4) EXPECT_TRUE(has(r.out, "note: 3D point features moved onto the mesh by up to")) << r.out;
        }
    }
}

TEST(RoundTripReliability, PointsCopiedWithFewDecimalsAreAcceptedAndFarOnesRefusedWithTheDistance) {
    TempDir d;
    const std::string mesh = data("meshes/nefertiti.off");
    const TriMesh m = read_mesh(mesh);
    Eigen::AlignedBox3d box;
    for (const Vec3& p : m.positions) box.extend(p);
    const double diag = box.diagonal().norm();
    const Tri& t = m.faces[300];
    const Vec3 a = m.positions[t[0]], b = m.positions[t[1]], c = m.positions[t[2]];
    const Vec3 centroid = (a + b + c) / 3, normal = (b - a).cross(c - a).normalized();
    auto features_with = [&](const Vec3& p) {
        std::ostringstream os;
        os.precision(17);
        os << R"({"image_size": [512, 512], "features": [{"name": "a", "vertex": 0, "image": [100, 100]},
            {"name": "b", "vertex": 8, "image": [400, 100]}, {"name": "c", "vertex": 7, "image": [250, 400]},
            {"name": "p", "point": [)" << p.x() << ", " << p.y() << ", " << p.z() << R"(], "image": [250, 200]}]})";
        return os.str();
    };
    // 2e-6 of the diagonal off the surface was refused (tolerance 1e-6): now accepted.
    write_file(d / "near.json", features_with(centroid + 2e-6 * diag * normal));
    RunResult r = run_ctmap("validate " + q(mesh) + " " + q(d / "near.json"));
    EXPECT_EQ(r.code, 0) << r.out;
    // 1e-3 of the diagonal: refused, saying how far and what accepts it.
    write_file(d / "far.json", features_with(centroid + 1e-3 * diag * normal));
    r = run_ctmap("validate " + q(mesh) + " " + q(d / "far.json"));
    EXPECT_EQ(r.code, kExitBadInput) << r.out;
    EXPECT_TRUE(has(r.out, "feature 'p'") && has(r.out, "away from the surface") && has(r.out, "--snap")) << r.out;
    // --snap accepts it; the map says how far the point moved, and is certified.
    r = run_ctmap("map " + q(mesh) + " " + q(d / "far.json") + " -o " + q(d / "far.obj") + " --snap 0.1");
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(has(r.out, "moved onto the mesh by up to")) << r.out;
    r = run_ctmap("check " + q(d / "far.obj") + " --features " + q(d / "far.json") + " --snap 0.1");
    EXPECT_EQ(r.code, 0) << r.out;
}

// ---------------------------------------------------------------------------------------------
// EXIF orientation.

/// A 64 x 32 JPEG whose quadrants are red (top left), green (top right), blue (bottom left) and
/// white (bottom right), with an EXIF block saying `orientation` (none when 0).
std::string quadrant_jpeg(int orientation) {
    const int w = 64, h = 32;
    std::vector<std::uint8_t> px(w * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const bool right = x >= w / 2, bottom = y >= h / 2;
            const std::uint8_t c[4][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}};
            std::memcpy(&px[(y * w + x) * 3], c[(bottom ? 2 : 0) + (right ? 1 : 0)], 3);
        }
    std::string jpg;
    stbi_write_jpg_to_func([](void* ctx, void* data, int n) { static_cast<std::string*>(ctx)->append((char*)data, n); },
                           &jpg, w, h, 3, px.data(), 95);
    if (orientation == 0) return jpg;
    // APP1 "Exif": a big-endian TIFF header and IFD0 with one entry, Orientation (0x0112, SHORT).
    const unsigned char app1[] = {0xFF, 0xE1, 0, 34, 'E', 'x', 'i', 'f', 0, 0, 'M', 'M', 0, 0x2A, 0, 0, 0, 8,
                                  0, 1, 0x01, 0x12, 0, 3, 0, 0, 0, 1, 0, (unsigned char)orientation, 0, 0,
                                  0, 0, 0, 0};
    return jpg.substr(0, 2) + std::string(reinterpret_cast<const char*>(app1), sizeof app1) + jpg.substr(2);
}

/// The colour name of the pixel at (x, y): r, g, b, w, or ? (JPEG: within 60 of pure).
char colour_at(const Image& img, int x, int y) {
    const std::uint8_t* p = &img.pixels[(std::size_t(y) * img.width + x) * 4];
    auto near = [&](int r, int g, int b) { return std::abs(p[0] - r) < 60 && std::abs(p[1] - g) < 60 && std::abs(p[2] - b) < 60; };
    return near(255, 0, 0) ? 'r' : near(0, 255, 0) ? 'g' : near(0, 0, 255) ? 'b' : near(255, 255, 255) ? 'w' : '?';
}

/// The four quadrant colours of `img`, top left, top right, bottom left, bottom right (sampled at
/// their centres).
std::string quadrants(const Image& img) {
    const int qx = img.width / 4, qy = img.height / 4;
    return {colour_at(img, qx, qy), colour_at(img, 3 * qx, qy), colour_at(img, qx, 3 * qy), colour_at(img, 3 * qx, 3 * qy)};
}

TEST(RoundTripReliability, JpegPhotosAreReadUprightByTheirExifOrientation) {
    TempDir d;
    // What a viewer shows for each orientation (EXIF 2.3 / TIFF 6.0, tag 274), as quadrant colours
    // TL TR BL BR of the stored picture "rgbw".
    const struct {
        int orientation;
        int width, height;
        const char* shown;
    } cases[] = {{0, 64, 32, "rgbw"}, {1, 64, 32, "rgbw"}, {2, 64, 32, "grwb"}, {3, 64, 32, "wbgr"},
                 {4, 64, 32, "bwrg"}, {5, 32, 64, "rbgw"}, {6, 32, 64, "brwg"}, {7, 32, 64, "wgbr"},
                 {8, 32, 64, "gwrb"}};
    for (const auto& c : cases) {
        SCOPED_TRACE("orientation " + std::to_string(c.orientation));
        const std::string file = d / ("o" + std::to_string(c.orientation) + ".jpg");
        write_file(file, quadrant_jpeg(c.orientation));
        const Image img = read_image(file);
        EXPECT_EQ(img.width, c.width);
        EXPECT_EQ(img.height, c.height);
        EXPECT_EQ(quadrants(img), c.shown);
        int w = 0, h = 0;
        read_image_size(file, w, h);
        EXPECT_EQ(w, c.width);
        EXPECT_EQ(h, c.height);
    }
    // The GLB that `map` writes embeds the upright picture (as PNG) for a turned JPEG.
    const std::string photo = d / "o6.jpg";
    write_file(d / "f.json", R"({"features": [{"name": "a", "vertex": 0, "image": [2, 2]},
        {"name": "b", "vertex": 8, "image": [30, 2]}, {"name": "c", "vertex": 7, "image": [16, 60]}]})");
    const RunResult r = run_ctmap("map " + q(data("meshes/nefertiti.off")) + " " + q(d / "f.json") + " --image " +
                                  q(photo) + " -o " + q(d / "m.obj") + " --glb " + q(d / "m.glb"));
    ASSERT_EQ(r.code, 0) << r.out;  // (2, 60) lies only in the upright 32 x 64 picture
    EXPECT_TRUE(has(r.out, "(32 x 64)")) << r.out;
    GlbTexture tex;
    read_glb(d / "m.glb", &tex);
    EXPECT_EQ(tex.mime_type, "image/png");
    const Image embedded = decode_image(std::string(tex.bytes.begin(), tex.bytes.end()), "m.glb");
    EXPECT_EQ(quadrants(embedded), "brwg");
}

// ---------------------------------------------------------------------------------------------
// The GLB `map` writes is read by `check` and `render`; `check` names its files.

// The tests that draw (`ctmap render`) are named Render*: scripts/test.sh leaves them out of the
// sanitizer pass, whose LeakSanitizer reports Mesa's llvmpipe's own allocations.

TEST(RenderReliability, RendersTheGlbThatMapWritesWithItsEmbeddedTexture) {
    TempDir d;
    const RunResult m = run_ctmap("map " + q(data("meshes/nefertiti.off")) + " " + q(data("features/nefertiti_astronaut.json")) +
                                  " --image " + q(data("images/astronaut.png")) + " -o " + q(d / "m.obj") + " --glb " +
                                  q(d / "m.glb") + " -q");
    ASSERT_EQ(m.code, 0) << m.out;
    for (const char* mode : {"textured", "checker", "uv"}) {  // no --image: the GLB's own texture
        const RunResult r = run_ctmap("render " + q(d / "m.glb") + " -o " + q(d / "m.png") + " --size 96 -q --mode " + mode);
        EXPECT_EQ(r.code, 0) << mode << "\n" << r.out;
        const Image pic = read_image(d / "m.png");
        EXPECT_EQ(pic.width, 96);
    }
}

TEST(RoundTripReliability, CheckReadsTheGlbThatMapWritesAndNamesItsFiles) {
    TempDir d;
    const std::string features = data("features/nefertiti_astronaut.json");
    RunResult r = run_ctmap("map " + q(data("meshes/nefertiti.off")) + " " + q(features) + " --image " +
                            q(data("images/astronaut.png")) + " -o " + q(d / "m.obj") + " --glb " + q(d / "m.glb"));
    ASSERT_EQ(r.code, 0) << r.out;
    const std::string summary = insertion_summary(r.out);
    ASSERT_FALSE(summary.empty()) << r.out;
    const std::string faces = summary.substr(summary.rfind(", ") + 2);  // "N faces"
    r = run_ctmap("check " + q(d / "m.glb") + " --features " + q(features));
    EXPECT_EQ(r.code, 0) << r.out;
    const std::string triangles = faces.substr(0, faces.find(' ')) + " triangles";
    EXPECT_TRUE(has(r.out, "m.glb: valid (" + triangles + ", 16 features)")) << r.out << "\nmap said: " << summary;
    // A map without UVs, and features that are not on the map: both messages name the files.
    r = run_ctmap("convert " + q(data("meshes/nefertiti.off")) + " -o " + q(d / "plain.obj"));
    ASSERT_EQ(r.code, 0) << r.out;
    r = run_ctmap("check " + q(d / "plain.obj") + " --features " + q(features));
    EXPECT_EQ(r.code, kExitBadInput);
    EXPECT_TRUE(has(r.out, d / "plain.obj") && has(r.out, "no texture coordinates")) << r.out;
    write_file(d / "far.json", R"({"image_size": [512, 512], "features": [{"name": "a", "vertex": 0, "image": [1, 1]},
        {"name": "b", "vertex": 8, "image": [9, 1]}, {"name": "p", "point": [100, 100, 100], "image": [5, 9]}]})");
    r = run_ctmap("check " + q(d / "m.obj") + " --features " + q(d / "far.json"));
    EXPECT_EQ(r.code, kExitBadInput);
    EXPECT_TRUE(has(r.out, d / "far.json") && has(r.out, d / "m.obj") && has(r.out, "feature 'p'")) << r.out;
}

// ---------------------------------------------------------------------------------------------
// Outputs as Blender and three.js want them: normals, one group per patch, a movable texture.

/// The lines of `text` starting with `prefix`.
std::vector<std::string> lines_starting(const std::string& text, const std::string& prefix) {
    std::vector<std::string> out;
    std::istringstream is(text);
    for (std::string l; std::getline(is, l);)
        if (l.rfind(prefix, 0) == 0) out.push_back(l);
    return out;
}

TEST(RoundTripReliability, ObjAndGlbCarryVertexNormalsAndOneGroupPerPatch) {
    TempDir d;
    RunResult r = run_ctmap("map " + q(data("meshes/nefertiti.off")) + " " + q(data("features/nefertiti_astronaut.json")) +
                            " -o " + q(d / "m.obj") + " --glb " + q(d / "m.glb") + " -q");
    ASSERT_EQ(r.code, 0) << r.out;
    const std::string obj = read_file(d / "m.obj");
    // 22 patches: 22 groups, each named once (the faces of a patch together; there were 10,644
    // switches on a big map).
    const auto groups = lines_starting(obj, "g ");
    EXPECT_EQ(groups.size(), 22u);
    EXPECT_EQ(std::set<std::string>(groups.begin(), groups.end()).size(), groups.size());
    // One unit normal per vertex, on the side the faces face (a smooth mask: every corner).
    const TexturedMesh tm = read_textured_obj(d / "m.obj");
    const auto vn = lines_starting(obj, "vn ");
    ASSERT_EQ(vn.size(), tm.mesh.positions.size());
    std::vector<Vec3> normals;
    for (const std::string& l : vn) {
        std::istringstream is(l.substr(3));
        Vec3 n;
        is >> n.x() >> n.y() >> n.z();
        EXPECT_NEAR(n.norm(), 1.0, 1e-12);
        normals.push_back(n);
    }
    for (const std::string& f : lines_starting(obj, "f ")) {  // f v/vt/vn with vn = v
        std::istringstream is(f.substr(2));
        for (std::string c; is >> c;) {
            const std::string v = c.substr(0, c.find('/')), n = c.substr(c.rfind('/') + 1);
            ASSERT_EQ(v, n) << f;
        }
    }
    int facing = 0, corners = 0;
    for (const Tri& t : tm.mesh.faces) {
        const Vec3 fn = (tm.mesh.positions[t[1]] - tm.mesh.positions[t[0]]).cross(tm.mesh.positions[t[2]] - tm.mesh.positions[t[0]]);
        for (int k = 0; k < 3; ++k, ++corners) facing += fn.dot(normals[t[k]]) > 0;
    }
    EXPECT_EQ(facing, corners);
    // The GLB: a NORMAL attribute with one unit vector per glTF vertex.
    const std::string glb = read_file(d / "m.glb");
    std::uint32_t json_len = 0;
    std::memcpy(&json_len, glb.data() + 12, 4);
    const auto doc = nlohmann::json::parse(glb.substr(20, json_len));
    const auto& attributes = doc["meshes"][0]["primitives"][0]["attributes"];
    ASSERT_TRUE(attributes.contains("NORMAL")) << attributes.dump();
    const auto& acc = doc["accessors"][attributes["NORMAL"].get<int>()];
    EXPECT_EQ(acc["count"], doc["accessors"][attributes["POSITION"].get<int>()]["count"]);
    const auto& view = doc["bufferViews"][acc["bufferView"].get<int>()];
    const std::size_t bin = 20 + json_len + 8, offset = view.value("byteOffset", 0);
    for (int i = 0; i < acc["count"].get<int>(); ++i) {
        float n[3];
        std::memcpy(n, glb.data() + bin + offset + 12 * std::size_t(i), 12);
        ASSERT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-6) << i;
    }
}

TEST(RenderReliability, CopyImageMakesTheObjMovableWithItsTexture) {
    TempDir d;
    fs::create_directories(d / "photos");
    fs::create_directories(d / "out");
    fs::copy_file(data("images/astronaut.png"), d / "photos/astronaut.png");
    const std::string base = "map " + q(data("meshes/nefertiti.off")) + " " + q(data("features/nefertiti_astronaut.json")) +
                             " --image " + q(d / "photos/astronaut.png") + " -q";
    RunResult r = run_ctmap(base + " -o " + q(d / "out/m.obj") + " --copy-image");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(read_file(d / "out/astronaut.png"), read_file(d / "photos/astronaut.png"));
    EXPECT_TRUE(has(read_file(d / "out/m.mtl"), "map_Kd astronaut.png\n"));
    // Moved elsewhere, without the photos folder: the material still finds its texture.
    fs::rename(d / "out", d / "moved");
    fs::remove_all(d / "photos");
    r = run_ctmap("render " + q(d / "moved/m.obj") + " -o " + q(d / "moved/m.png") + " --size 64 -q");
    EXPECT_EQ(r.code, 0) << r.out;
}

TEST(RoundTripReliability, AnExifTurnedPhotoGivesTheObjAnUprightTexture) {
    TempDir d;
    write_file(d / "o6.jpg", quadrant_jpeg(6));
    write_file(d / "f.json", R"({"features": [{"name": "a", "vertex": 0, "image": [2, 2]},
        {"name": "b", "vertex": 8, "image": [30, 2]}, {"name": "c", "vertex": 7, "image": [16, 60]}]})");
    const RunResult r = run_ctmap("map " + q(data("meshes/nefertiti.off")) + " " + q(d / "f.json") + " --image " +
                                  q(d / "o6.jpg") + " -o " + q(d / "m.obj"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(has(r.out, "EXIF orientation")) << r.out;
    EXPECT_TRUE(has(read_file(d / "m.mtl"), "map_Kd m_texture.png\n"));
    const Image upright = read_image(d / "m_texture.png");
    EXPECT_EQ(upright.width, 32);
    EXPECT_EQ(quadrants(upright), "brwg");
}

/// `mesh` as BINARY OFF (Geomview's form, as CGAL reads it): big-endian counts, float32
/// coordinates, then per face its corner count and indices.
std::string binary_off(const TriMesh& mesh) {
    std::string out = "OFF BINARY\n";
    auto put = [&](std::uint32_t v) {
        for (int s = 24; s >= 0; s -= 8) out += char((v >> s) & 0xff);
    };
    put(mesh.num_vertices()), put(mesh.num_faces()), put(0);
    for (const Vec3& p : mesh.positions)
        for (int k = 0; k < 3; ++k) {
            const float f = float(p[k]);
            std::uint32_t bits;
            std::memcpy(&bits, &f, 4);
            put(bits);
        }
    for (const Tri& t : mesh.faces) put(3), put(t[0]), put(t[1]), put(t[2]);
    return out;
}

// The corner counts of a BINARY OFF are walked before CGAL allocates them (a fuzz finding): a
// real binary file must still be read whole, face for face, at float32 precision.
TEST(RoundTripReliability, ABinaryOffIsReadFaceForFace) {
    TempDir d;
    const TriMesh text = read_mesh(data("meshes/nefertiti.off"));
    write_file(d / "bin.off", binary_off(text));
    const TriMesh bin = read_mesh(d / "bin.off");
    ASSERT_EQ(bin.num_vertices(), text.num_vertices());
    ASSERT_EQ(bin.num_faces(), text.num_faces());
    for (int f = 0; f < text.num_faces(); ++f) EXPECT_EQ(bin.faces[f], text.faces[f]) << "face " << f;
    double worst = 0;
    for (int v = 0; v < text.num_vertices(); ++v)
        for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(bin.positions[v][k] - double(float(text.positions[v][k]))));
    EXPECT_EQ(worst, 0.0) << "a coordinate is not its float32 value";
    const RunResult r = run_ctmap("info " + q(d / "bin.off"));
    EXPECT_EQ(r.code, 0) << r.out;
}

}  // namespace
}  // namespace ctmap::test

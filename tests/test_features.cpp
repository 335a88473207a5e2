// features.json (DESIGN §4): units, where the image is, 3D point features, and messages that
// name the features involved.
#include <nlohmann/json.hpp>

#include "ctmap/errors.h"
#include "ctmap/io/features.h"
#include "ctmap/io/read_mesh.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

/// The problem text of the BadInput that `f` throws (empty, and a failure, if it throws none).
template <class F>
std::string problem_of(F&& f) {
    try {
        f();
    } catch (const BadInput& e) {
        return e.problem();
    }
    ADD_FAILURE() << "no BadInput thrown";
    return {};
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(Features, UvUnitsBecomePixelsWithVFlipped) {
    // UV = (x / W, 1 - y / H) (DESIGN §3): the UV origin is the image's bottom-left corner.
    FeatureSet fs = parse_features(R"({"units": "uv", "features": [
        {"name": "bottom_left", "vertex": 0, "image": [0, 0]},
        {"name": "top_right", "vertex": 1, "image": [1, 1]},
        {"name": "inner", "vertex": 2, "image": [0.25, 0.75]},
        {"name": "third", "vertex": 3, "image": [0.1, 0.3]}]})",
                                   "f.json");
    EXPECT_EQ(fs.units, "uv");
    resolve_units(fs, 640, 480);
    EXPECT_EQ(fs.units, "pixels");
    EXPECT_EQ(fs.features[0].image, Vec2(0, 480));
    EXPECT_EQ(fs.features[1].image, Vec2(640, 0));
    EXPECT_EQ(fs.features[2].image, Vec2(160, 120));  // binary fractions: exact
    EXPECT_DOUBLE_EQ(fs.features[3].image.x(), 64.0);
    EXPECT_DOUBLE_EQ(fs.features[3].image.y(), 336.0);
    // And back: the pixel point's UV is the UV that was given, to rounding.
    EXPECT_NEAR(fs.features[3].image.x() / 640, 0.1, 1e-16);
    EXPECT_NEAR(1 - fs.features[3].image.y() / 480, 0.3, 1e-16);
}

TEST(Features, PixelUnitsAreKeptAndCheckedAgainstTheImage) {
    FeatureSet fs = parse_features(R"({"features": [
        {"name": "a", "vertex": 0, "image": [0, 0]},
        {"name": "b", "vertex": 1, "image": [640, 480]},
        {"name": "c", "vertex": 2, "image": [320.5, 0.25]}]})",
                                   "f.json");
    EXPECT_EQ(fs.units, "pixels");  // the default
    FeatureSet copy = fs;
    resolve_units(copy, 640, 480);  // the corners are inside: pixels cover [0, W] x [0, H]
    for (std::size_t i = 0; i < fs.features.size(); ++i) EXPECT_EQ(copy.features[i].image, fs.features[i].image);
    const std::string p = problem_of([&] { resolve_units(fs, 640, 479); });
    EXPECT_TRUE(has(p, "feature 'b'")) << p;
    EXPECT_TRUE(has(p, "outside the 640 x 479 image")) << p;
    EXPECT_FALSE(has(p, "'a'")) << p;
}

TEST(Features, ImageIsResolvedAgainstTheFeaturesFile) {
    const char* body = R"(, "features": [{"name": "a", "vertex": 0, "image": [1, 2]},
        {"name": "b", "vertex": 1, "image": [3, 4]}, {"name": "c", "vertex": 2, "image": [5, 6]}]})";
    EXPECT_EQ(parse_features(std::string(R"({"image": "photo.png")") + body, "/data/set/f.json").image,
              "/data/set/photo.png");
    EXPECT_EQ(parse_features(std::string(R"({"image": "../img/./photo.png")") + body, "/data/set/f.json").image,
              "/data/img/photo.png");
    EXPECT_EQ(parse_features(std::string(R"({"image": "/abs/photo.png")") + body, "/data/set/f.json").image,
              "/abs/photo.png");
    EXPECT_EQ(parse_features(std::string(R"({"image": "photo.png")") + body, "f.json").image, "photo.png");
    EXPECT_EQ(parse_features(std::string(R"({"units": "pixels")") + body, "/data/f.json").image, "");
}

TEST(Features, CliFindsTheImageBesideTheFeaturesFileAndArgumentOverridesIt) {
    TempDir dir;
    std::filesystem::create_directories(dir / "set/img");
    std::filesystem::copy_file(data("images/astronaut.png"), dir / "set/img/photo.png");
    write_file(dir / "set/f.json", R"({"image": "img/photo.png", "features": [
        {"name": "a", "vertex": 0, "image": [500, 500]}, {"name": "b", "vertex": 8, "image": [3, 4]},
        {"name": "c", "vertex": 7, "image": [5, 6]}]})");
    const std::string mesh = data("meshes/nefertiti.off");
    // Run from another folder: the image is found relative to the features file, not the cwd.
    RunResult r = run_ctmap("validate " + q(mesh) + " " + q(dir / "set/f.json"));
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(has(r.out, "512 x 512")) << r.out;
    EXPECT_TRUE(has(r.out, dir / "set/img/photo.png")) << r.out;
    // --image overrides it, but the pixels were picked on the 512 x 512 photo: a 451 x 300 image is
    // refused with both sizes named (issue 17: the map would be certified and wrong).
    r = run_ctmap("validate " + q(mesh) + " " + q(dir / "set/f.json") + " --image " + q(data("images/chelsea.png")));
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_TRUE(has(r.out, "photo.png (512 x 512)")) << r.out;
    EXPECT_TRUE(has(r.out, "is 451 x 300")) << r.out;
    // Without an image of its own, the points are checked against the image given: a (500, 500) is
    // outside the 451 x 300 one.
    write_file(dir / "set/g.json", R"({"features": [
        {"name": "a", "vertex": 0, "image": [500, 500]}, {"name": "b", "vertex": 8, "image": [3, 4]},
        {"name": "c", "vertex": 7, "image": [5, 6]}]})");
    r = run_ctmap("validate " + q(mesh) + " " + q(dir / "set/g.json") + " --image " + q(data("images/chelsea.png")));
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_TRUE(has(r.out, "feature 'a'")) << r.out;
    EXPECT_TRUE(has(r.out, "outside the 451 x 300 image")) << r.out;
}

TEST(Features, PointFeaturesMustLieOnTheSurface) {
    const std::string mesh_file = data("meshes/nefertiti.off");
    const TriMesh mesh = read_mesh(mesh_file);
    Eigen::AlignedBox3d box;
    for (const Vec3& p : mesh.positions) box.extend(p);
    const double diag = box.diagonal().norm();
    const Tri& t = mesh.faces[100];
    const Vec3 a = mesh.positions[t[0]], b = mesh.positions[t[1]], c = mesh.positions[t[2]];
    const Vec3 centroid = (a + b + c) / 3;
    const Vec3 normal = (b - a).cross(c - a).normalized();

    auto features_at = [&](const Vec3& p) {
        FeatureSet fs;
        fs.path = "f.json";
        fs.features = {{"fixed", 0, std::nullopt, Vec2(1, 1)},
                       {"tip", -1, p, Vec2(2, 2)},
                       {"other", 5, std::nullopt, Vec2(3, 3)}};
        return fs;
    };
    EXPECT_NO_THROW(check_features_on_mesh(features_at(centroid), mesh, mesh_file));
    EXPECT_NO_THROW(check_features_on_mesh(features_at(a), mesh, mesh_file));  // on a vertex
    // Within the tolerance (1e-6 of the bounding-box diagonal) off the surface: accepted.
    EXPECT_NO_THROW(check_features_on_mesh(features_at(centroid + 0.5e-6 * diag * normal), mesh, mesh_file));
    // Beyond it: refused, naming the feature and the mesh, and only that feature.
    const std::string p =
        problem_of([&] { check_features_on_mesh(features_at(centroid + 1e-3 * diag * normal), mesh, mesh_file); });
    EXPECT_TRUE(has(p, "feature 'tip'")) << p;
    EXPECT_TRUE(has(p, "away from the surface of " + mesh_file)) << p;
    EXPECT_FALSE(has(p, "'fixed'")) << p;
    EXPECT_FALSE(has(p, "'other'")) << p;
}

TEST(Features, EveryViolationIsReportedWithTheFeaturesInvolved) {
    // Three problems at once: all three in one message, each naming its features.
    const std::string p = problem_of([] {
        parse_features(R"({"features": [
            {"name": "eye", "vertex": 3, "image": [1, 2]},
            {"name": "eye", "vertex": 4, "image": [5, 6]},
            {"name": "nose", "vertex": 3, "image": [7, 8]},
            {"name": "chin", "vertex": 9, "image": [5, 6]}]})",
                       "f.json");
    });
    EXPECT_TRUE(has(p, "the name 'eye' is used by more than one feature")) << p;
    EXPECT_TRUE(has(p, "features 'eye' and 'nose' both use vertex 3")) << p;
    EXPECT_TRUE(has(p, "features 'eye' and 'chin' have the same image point (5, 6)")) << p;

    const std::string q2 = problem_of([] {
        parse_features(R"({"features": [
            {"name": "a", "point": [0, 0, 0], "image": [1, 2]},
            {"name": "b", "point": [0, 0, 0], "image": [3, 4]},
            {"name": "c", "vertex": 1, "image": [5, 6]}]})",
                       "f.json");
    });
    EXPECT_TRUE(has(q2, "features 'a' and 'b' are the same 3D point")) << q2;
}

TEST(Features, VertexBeyondTheMeshNamesFeatureAndMesh) {
    FeatureSet fs = parse_features(R"({"features": [
        {"name": "ok", "vertex": 298, "image": [1, 2]},
        {"name": "far", "vertex": 299, "image": [3, 4]},
        {"name": "farther", "vertex": 1000, "image": [5, 6]}]})",
                                   "f.json");
    const std::string mesh_file = data("meshes/nefertiti.off");
    const std::string p = problem_of([&] { check_features_on_mesh(fs, read_mesh(mesh_file), mesh_file); });
    EXPECT_TRUE(has(p, "feature 'far' uses vertex 299, but " + mesh_file + " has only 299 vertices")) << p;
    EXPECT_TRUE(has(p, "feature 'farther' uses vertex 1000")) << p;
    EXPECT_FALSE(has(p, "'ok'")) << p;
}

TEST(Features, JsonRoundTripAndTheShippedExample) {
    const std::string path = data("features/nefertiti_astronaut.json");
    const FeatureSet fs = read_features(path);
    ASSERT_GE(fs.features.size(), 3u);
    const FeatureSet again = parse_features(features_to_json(fs), path);
    ASSERT_EQ(again.features.size(), fs.features.size());
    for (std::size_t i = 0; i < fs.features.size(); ++i) {
        EXPECT_EQ(again.features[i].name, fs.features[i].name);
        EXPECT_EQ(again.features[i].vertex, fs.features[i].vertex);
        EXPECT_EQ(again.features[i].image, fs.features[i].image);  // nlohmann prints doubles exactly
    }
    EXPECT_EQ(again.image_size, fs.image_size);
    // The shipped example is valid on the shipped mesh and image.
    const RunResult r = run_ctmap("validate " + q(data("meshes/nefertiti.off")) + " " + q(path) + " --image " +
                                  q(data("images/astronaut.png")));
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(has(r.out, std::to_string(fs.features.size()) + " features")) << r.out;
}

}  // namespace
}  // namespace ctmap::test

// `ctmap map` and `ctmap demo` as users run them (issue 4, must-show 1 and 2): the real cases
// (nefertiti/astronaut, lion-head/chelsea, mannequin-devil and mushroom on coffee, three_peaks on
// astronaut) mapped by the program, the written OBJ certified again from the file (here, and by
// `ctmap check`), the report's figures compared with that recomputation, the GLB read back with
// the same UVs as floats; refinement must lower the symmetric Dirichlet mean. Failures leave the
// output folder empty.
#include <nlohmann/json.hpp>
#include <ostream>

#include "ctmap/certify/certificate.h"
#include "ctmap/io/features.h"
#include "ctmap/io/glb_io.h"
#include "ctmap/io/obj_io.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

struct RealCase {
    const char* mesh;
    const char* features;
    const char* image;
};

// Test listings and failures name the case instead of printing its bytes.
void PrintTo(const RealCase& c, std::ostream* os) { *os << c.mesh << " / " << c.features << " / " << c.image; }

const RealCase kCases[] = {{"nefertiti", "nefertiti_astronaut", "astronaut"},
                           {"lion-head", "lion-head_chelsea", "chelsea"},
                           {"mannequin-devil", "mannequin-devil_coffee", "coffee"},
                           {"mushroom", "mushroom_coffee", "coffee"},
                           {"three_peaks", "three_peaks_astronaut", "astronaut"}};

class MapCli : public ::testing::TestWithParam<RealCase> {};

TEST_P(MapCli, RealCaseIsCertifiedFromTheWrittenFiles) {
    const RealCase& c = GetParam();
    TempDir dir;
    const std::string mesh = data(std::string("meshes/") + c.mesh + ".off");
    const std::string features = data(std::string("features/") + c.features + ".json");
    const std::string image = data(std::string("images/") + c.image + ".png");
    const RunResult r = run_ctmap("map " + q(mesh) + " " + q(features) + " --image " + q(image) + " -o " +
                                  q(dir / "m.obj") + " --glb " + q(dir / "m.glb") + " --report " + q(dir / "r.json"));
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("certificate: valid"), std::string::npos) << r.out;

    // The certificate recomputed here from the files, with the feature UVs from the features
    // file by the documented rule (DESIGN §3), not from anything ctmap wrote.
    std::string mtl_image;
    const TexturedMesh tm = read_textured_obj(dir / "m.obj", &mtl_image);
    EXPECT_TRUE(std::filesystem::equivalent(mtl_image, image)) << mtl_image;
    FeatureSet fs = read_features(features);
    int w = 0, h = 0;
    resolve_feature_image(fs, image, w, h);
    std::vector<int> fv;
    std::vector<Vec2> fuv;
    for (const Feature& f : fs.features) {
        ASSERT_GE(f.vertex, 0) << "these files name vertices";
        fv.push_back(f.vertex);  // the input's vertices keep their index (DESIGN §3)
        fuv.push_back(image_to_uv(f.image, w, h));
    }
    const Certificate cert = certify(tm, fv, fuv);
    EXPECT_TRUE(cert.valid);
    EXPECT_EQ(cert.flipped, 0);
    EXPECT_EQ(cert.degenerate, 0);
    EXPECT_EQ(cert.feature_max_error, 0.0);
    EXPECT_TRUE(cert.border_simple);

    // `ctmap check` says the same.
    const RunResult chk = run_ctmap("check " + q(dir / "m.obj") + " --features " + q(features) + " --image " + q(image));
    EXPECT_EQ(chk.code, 0) << chk.out;

    // The report: what was written, measured again.
    const nlohmann::json rep = nlohmann::json::parse(read_file(dir / "r.json"));
    EXPECT_EQ(rep["certificate"]["valid"], true);
    EXPECT_EQ(rep["certificate"]["flipped"], 0);
    EXPECT_EQ(rep["certificate"]["feature_max_error"], 0.0);
    EXPECT_EQ(rep["counts"]["faces"], tm.mesh.num_faces());
    EXPECT_EQ(rep["counts"]["vertices"], tm.mesh.num_vertices());
    EXPECT_EQ(rep["counts"]["features"], fs.features.size());
    const double sd = rep["certificate"]["symmetric_dirichlet"], sd0 = rep["distortion_before_refine"]["symmetric_dirichlet"];
    EXPECT_NEAR(sd, cert.distortion.symmetric_dirichlet, 1e-9 * cert.distortion.symmetric_dirichlet);
    EXPECT_LT(sd, sd0) << "refinement must lower the symmetric Dirichlet mean";
    for (const char* k : {"read", "triangulate", "paths", "embed", "refine", "total"}) {
        ASSERT_TRUE(rep["timings_ms"].contains(k)) << k;
        EXPECT_GE(rep["timings_ms"][k].get<double>(), 0.0) << k;
    }
    EXPECT_GE(rep["timings_ms"]["total"].get<double>(), rep["timings_ms"]["paths"].get<double>());

    // The GLB holds the same map as floats (glTF stores v flipped: the reader undoes it).
    const TexturedMesh glb = read_glb(dir / "m.glb");
    ASSERT_EQ(glb.mesh.faces, tm.mesh.faces);
    int off = 0;
    for (std::size_t f = 0; f < tm.mesh.faces.size(); ++f)
        for (int k = 0; k < 3; ++k) {
            const Vec2& a = tm.uvs[tm.uv_faces[f][k]];
            const Vec2& b = glb.uvs[glb.uv_faces[f][k]];
            off += float(a.x()) != float(b.x()) || std::abs(double(float(a.y())) - b.y()) > 1e-7;
        }
    EXPECT_EQ(off, 0);
    std::cout << c.mesh << ": " << rep["counts"]["features"] << " features, " << rep["counts"]["faces"]
              << " faces, symmetric Dirichlet " << sd0 << " -> " << sd << "\n";
}

INSTANTIATE_TEST_SUITE_P(RealCases, MapCli, ::testing::ValuesIn(kCases),
                         [](const auto& info) {
                             std::string n = info.param.mesh;
                             for (char& ch : n)
                                 if (!std::isalnum((unsigned char)ch)) ch = '_';
                             return n;
                         });

TEST(MapCliErrors, BorderOrderAgainstTheMeshIsBadInputAndWritesNothing) {
    TempDir dir;
    // Two border features of nefertiti swap their image points: the image border then runs in
    // another order than the mesh border.
    const std::string text = read_file(data("features/nefertiti_astronaut.json"));
    nlohmann::json j = nlohmann::json::parse(text);
    auto& f = j["features"];
    std::swap(f[0]["image"], f[2]["image"]);
    write_file(dir / "swapped.json", j.dump());
    std::filesystem::create_directories(dir.path() / "out");
    const RunResult r = run_ctmap("map " + q(data("meshes/nefertiti.off")) + " " + q(dir / "swapped.json") + " --image " +
                                  q(data("images/astronaut.png")) + " -o " + q(dir / "out/m.obj") + " --report " +
                                  q(dir / "out/r.json"));
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_NE(r.out.find("swapped.json"), std::string::npos) << r.out;
    EXPECT_TRUE(std::filesystem::is_empty(dir.path() / "out"));
}

TEST(MapCliErrors, MissingImageAndMissingFolderAreBadInput) {
    TempDir dir;
    const std::string base = "map " + q(data("meshes/nefertiti.off")) + " " + q(data("features/nefertiti_astronaut.json"));
    RunResult r = run_ctmap(base + " --image " + q(dir / "nope.png") + " -o " + q(dir / "m.obj"));
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_NE(r.out.find("nope.png"), std::string::npos) << r.out;
    r = run_ctmap(base + " --image " + q(data("images/astronaut.png")) + " -o " + q(dir / "no/such/folder/m.obj"));
    EXPECT_EQ(r.code, 2) << r.out;
    r = run_ctmap(base + " --image " + q(data("images/astronaut.png")) + " -o " + q(dir / "m.png"));
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_EQ(dir.count(), 0);
}

TEST(Demo, WritesTheCertifiedExampleAndItsGallery) {
    TempDir dir;
    const RunResult r = run_ctmap("demo --out " + q(dir / "demo"));
    ASSERT_EQ(r.code, 0) << r.out;
    const RunResult chk = run_ctmap("check " + q(dir / "demo/nefertiti.obj") + " --features " +
                                    q(data("features/nefertiti_astronaut.json")) + " --image " +
                                    q(data("images/astronaut.png")));
    EXPECT_EQ(chk.code, 0) << chk.out;
    const std::string html = read_file(dir / "demo/index.html");
    for (const char* png : {"nefertiti_textured.png", "nefertiti_checker.png", "nefertiti_uv.png", "nefertiti_paths.png",
                            "nefertiti_triangulation.png"}) {
        EXPECT_NE(html.find(png), std::string::npos) << png;
        EXPECT_GT(std::filesystem::file_size(dir / (std::string("demo/") + png)), 1000u) << png;
    }
}

}  // namespace
}  // namespace ctmap::test

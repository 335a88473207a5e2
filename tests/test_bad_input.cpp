// The bad-input suite (issue 2, point 3): every class of broken mesh, features file and image,
// run through the real `ctmap` program. Each case must give exit code 2 (DESIGN §3), a message
// that names the file and the problem, no crash, and no output file or temporary left behind.
// scripts/test.sh runs this suite again under AddressSanitizer + UndefinedBehaviorSanitizer
// (`ctest -R BadInput`), so every test name here contains "BadInput".
#include <cstdint>
#include <cstring>
#include <functional>
#include <random>

#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"
#include "ctmap/io/features.h"
#include "ctmap/io/image.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
#include "bad_input_support.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

// ---------------------------------------------------------------------------------------------
// Broken inputs, made on the spot.

/// `n` deterministic pseudo-random bytes with a NUL in them: binary garbage.
std::string garbage(std::size_t n, unsigned seed) {
    std::mt19937 g(seed);
    std::string s(n, '\0');
    for (char& c : s) c = char(g() & 0xff);
    s[7] = '\0';
    return s;
}

const char* const kTriangleOff = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n";

/// A binary STL with one triangle whose corners are `a`, `b`, `c` (little-endian floats).
std::string binary_stl(std::array<float, 9> corners) {
    std::string s(80, 'x');  // a header that does not start with "solid"
    const std::uint32_t n = 1;
    s.append(reinterpret_cast<const char*>(&n), 4);
    const std::array<float, 3> normal{0, 0, 1};
    s.append(reinterpret_cast<const char*>(normal.data()), 12);
    s.append(reinterpret_cast<const char*>(corners.data()), 36);
    s.append(2, '\0');
    return s;
}

const char* const kPlyHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";

/// A valid features file for nefertiti.off on a 512 x 512 image, with `extra` members added.
std::string features_json(const std::string& features, const std::string& extra = "\"image_size\": [512, 512]") {
    return "{" + extra + (extra.empty() ? "" : ", ") + "\"features\": [" + features + "]}";
}
const char* const kThreeFeatures =
    R"({"name": "a", "vertex": 0, "image": [10, 20]},
       {"name": "b", "vertex": 8, "image": [300, 40]},
       {"name": "c", "vertex": 7, "image": [50, 400]})";  // a triangle: `validate` checks the layout too

std::string image_bytes() { return read_file(data("images/astronaut.png")); }

// ---------------------------------------------------------------------------------------------
// Broken meshes: `convert` (which would write an output) or `info`.

/// `convert MESH -o <dir>/out.obj` on a mesh file named `name` holding `content`.
CliRun convert_obj(const TempDir& d, const std::string& name, const std::string& content,
                std::vector<std::string> keywords) {
    write_file(d / name, content);
    return {"convert " + q(d / name) + " -o " + q(d / "out.obj"), d / name, std::move(keywords)};
}

/// Same, writing a binary glTF.
CliRun convert_glb(const TempDir& d, const std::string& name, const std::string& content,
                std::vector<std::string> keywords) {
    write_file(d / name, content);
    return {"convert " + q(d / name) + " -o " + q(d / "out.glb"), d / name, std::move(keywords)};
}

CliRun info(const TempDir& d, const std::string& name, const std::string& content, std::vector<std::string> keywords) {
    write_file(d / name, content);
    return {"info " + q(d / name), d / name, std::move(keywords)};
}

const Case kMeshCases[] = {
    {"EmptyOff", [](const TempDir& d) { return convert_obj(d, "m.off", "", {"empty"}); }},
    {"WhitespaceOnlyObj", [](const TempDir& d) { return convert_obj(d, "m.obj", " \n\n\t\n", {"no vertices"}); }},
    {"TruncatedOff",
     [](const TempDir& d) { return convert_obj(d, "m.off", "OFF\n10 1 0\n0 0 0\n1 0 0\n", {"truncated", "10 vertices"}); }},
    {"TruncatedOffFaces",
     [](const TempDir& d) {
         return convert_glb(d, "m.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n# the second face is missing\n",
                            {"truncated", "2 faces"});
     }},
    {"OffHeaderDeclaresBillions",  // must fail before any allocation for 2e9 vertices
     [](const TempDir& d) {
         return convert_obj(d, "m.off", "OFF\n2000000000 2000000000 0\n0 0 0\n", {"truncated", "2000000000 vertices"});
     }},
    {"TruncatedPly",
     [](const TempDir& d) { return convert_obj(d, "m.ply", std::string(kPlyHeader) + "0 0 0\n1 0 0\n", {"truncated"}); }},
    {"GarbageOff", [](const TempDir& d) { return convert_obj(d, "m.off", garbage(3000, 1), {"binary data", "OFF"}); }},
    {"GarbageObj", [](const TempDir& d) { return convert_obj(d, "m.obj", garbage(3000, 2), {"binary data", "OBJ"}); }},
    {"GarbagePly", [](const TempDir& d) { return convert_glb(d, "m.ply", garbage(3000, 3), {"binary data", "PLY"}); }},
    {"GarbageStl", [](const TempDir& d) { return convert_obj(d, "m.stl", garbage(3000, 4), {"binary STL", "garbage"}); }},
    {"OffWithoutHeader",
     [](const TempDir& d) { return convert_obj(d, "m.off", "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", {"OFF header"}); }},
    {"NanCoordinateOff",
     [](const TempDir& d) {
         return convert_obj(d, "m.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n", {"NaN", "vertex 1", "line 4"});
     }},
    {"InfinityCoordinateObj",
     [](const TempDir& d) {
         return convert_glb(d, "m.obj", "v 0 0 0\nv 1 0 0\nv 0 -inf 0\nf 1 2 3\n", {"infinity", "vertex 2"});
     }},
    {"NanCoordinatePly",
     [](const TempDir& d) {
         return info(d, "m.ply", std::string(kPlyHeader) + "0 0 0\n1 NaN 0\n0 1 0\n3 0 1 2\n", {"NaN", "vertex 1"});
     }},
    {"NanCoordinateBinaryStl",  // CGAL reads it: ctmap's own finiteness check must catch it
     [](const TempDir& d) {
         const float nan = std::numeric_limits<float>::quiet_NaN();
         return convert_obj(d, "m.stl", binary_stl({0, 0, 0, 1, 0, 0, 0, nan, 0}), {"NaN"});
     }},
    {"CoordinateBeyondDoubleOff",
     [](const TempDir& d) {
         return convert_obj(d, "m.off", "OFF\n3 1 0\n0 0 0\n1e999 0 0\n0 1 0\n3 0 1 2\n", {"out of the range", "1e999"});
     }},
    {"CoordinateBeyondFloatGlb",  // fine in OBJ, but glTF stores 32-bit floats
     [](const TempDir& d) {
         CliRun r = convert_glb(d, "m.off", "OFF\n3 1 0\n0 0 0\n1e300 0 0\n0 1 0\n3 0 1 2\n", {"32-bit", "vertex 1"});
         r.names_file = d / "out.glb";  // the mesh is fine; the output format cannot hold it
         return r;
     }},
    {"FaceIndexOutOfRangeOff",
     [](const TempDir& d) {
         return convert_obj(d, "m.off", std::string(kTriangleOff) + "3 0 1 7\n", {"out of range", "vertex 7"});
     }},
    {"FaceIndexOutOfRangeObj",
     [](const TempDir& d) { return convert_obj(d, "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n", {"out of range"}); }},
    {"FaceIndexOutOfRangePly",
     [](const TempDir& d) {
         return convert_obj(d, "m.ply", std::string(kPlyHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", {"out of range"});
     }},
    {"NegativeFaceIndexOff",
     [](const TempDir& d) {
         return convert_obj(d, "m.off", std::string(kTriangleOff) + "3 0 1 -1\n", {"'-1' is not a vertex index"});
     }},
    {"FaceWithTwoCornersOff",
     [](const TempDir& d) { return convert_obj(d, "m.off", std::string(kTriangleOff) + "2 0 1\n", {"at least 3"}); }},
    {"FaceWithTwoCornersObj",
     [](const TempDir& d) { return convert_glb(d, "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2\n", {"at least 3"}); }},
    {"UnknownExtension",
     [](const TempDir& d) { return convert_obj(d, "m.xyz", std::string(kTriangleOff) + "3 0 1 2\n", {"unknown mesh format"}); }},
    {"MissingFile",
     [](const TempDir& d) { return CliRun{"convert " + q(d / "nothing.off") + " -o " + q(d / "out.obj"), d / "nothing.off", {"no such mesh file"}}; }},
    {"DirectoryInsteadOfFile",
     [](const TempDir& d) {
         std::filesystem::create_directory(d / "folder.off");
         return CliRun{"info " + q(d / "folder.off"), d / "folder.off", {"directory"}};
     }},
};

// ---------------------------------------------------------------------------------------------
// Meshes that read fine but are not discs: `validate` with a valid features file.

CliRun validate_mesh(const TempDir& d, const std::string& off, std::vector<std::string> keywords) {
    write_file(d / "m.off", off);
    write_file(d / "f.json", features_json(R"({"name": "a", "vertex": 0, "image": [1, 2]},
                                                {"name": "b", "vertex": 1, "image": [3, 4]},
                                                {"name": "c", "vertex": 2, "image": [5, 7]})"));
    return {"validate " + q(d / "m.off") + " " + q(d / "f.json"), d / "m.off", std::move(keywords)};
}

const Case kTopologyCases[] = {
    {"NonManifoldEdge",  // three triangles on the edge 0-1
     [](const TempDir& d) {
         return validate_mesh(d, "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n",
                              {"1 non-manifold edge"});
     }},
    {"BowTie",  // two triangles sharing only vertex 0
     [](const TempDir& d) {
         return validate_mesh(d, "OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n3 0 1 2\n3 0 3 4\n",
                              {"1 non-manifold vertex"});
     }},
    {"TwoComponents",
     [](const TempDir& d) {
         return validate_mesh(d, "OFF\n6 2 0\n0 0 0\n1 0 0\n0 1 0\n5 0 0\n6 0 0\n5 1 0\n3 0 1 2\n3 3 4 5\n",
                              {"2 connected components"});
     }},
    {"ClosedTetrahedron",  // like cow.off: closed, so it needs a seam
     [](const TempDir& d) {
         return validate_mesh(d, "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n",
                              {"closed", "seam"});
     }},
    {"HoleGivesTwoBorderLoops",  // a square with a square hole: an annulus
     [](const TempDir& d) {
         return validate_mesh(d,
                              "OFF\n8 8 0\n0 0 0\n3 0 0\n3 3 0\n0 3 0\n1 1 0\n2 1 0\n2 2 0\n1 2 0\n"
                              "3 0 1 5\n3 0 5 4\n3 1 2 6\n3 1 6 5\n3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n",
                              {"2 border loops"});
     }},
    {"InconsistentOrientation",  // a quad whose second triangle is flipped
     [](const TempDir& d) {
         return validate_mesh(d, "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 3 2\n", {"oppositely oriented"});
     }},
};

// ---------------------------------------------------------------------------------------------
// Broken features files: `validate nefertiti.off FEATURES --image astronaut.png`.

CliRun validate_features(const TempDir& d, const std::string& json, std::vector<std::string> keywords) {
    write_file(d / "f.json", json);
    return {"validate " + q(data("meshes/nefertiti.off")) + " " + q(d / "f.json") + " --image " +
                q(data("images/astronaut.png")),
            d / "f.json", std::move(keywords)};
}

std::string three_with(const std::string& third) {
    return R"({"name": "a", "vertex": 0, "image": [10, 20]}, {"name": "b", "vertex": 8, "image": [30, 40]}, )" + third;
}

const Case kFeatureCases[] = {
    {"EmptyFeaturesFile", [](const TempDir& d) { return validate_features(d, "", {"empty"}); }},
    {"WhitespaceFeaturesFile", [](const TempDir& d) { return validate_features(d, "  \n\t\n", {"empty"}); }},
    {"InvalidJson",
     [](const TempDir& d) { return validate_features(d, R"({"features": [{"name": "a",)", {"not valid JSON"}); }},
    {"NotAnObject", [](const TempDir& d) { return validate_features(d, "[1, 2, 3]", {"JSON object"}); }},
    {"MissingFeaturesArray",
     [](const TempDir& d) { return validate_features(d, R"({"units": "pixels"})", {"missing field \"features\""}); }},
    {"EmptyFeaturesArray", [](const TempDir& d) { return validate_features(d, features_json(""), {"at least one"}); }},
    {"FeatureMissingFields",
     [](const TempDir& d) {
         return validate_features(d,
                                  features_json(R"({"name": "a", "image": [1, 2]}, {"vertex": 1, "image": [3, 4]},
                                                   {"name": "c", "vertex": 2})"),
                                  {"feature 'a': give exactly one of \"vertex\"", "feature #1: missing field \"name\"",
                                   "feature 'c': missing field \"image\""});
     }},
    {"WrongUnits",
     [](const TempDir& d) {
         return validate_features(d, features_json(kThreeFeatures, R"("units": "mm")"), {"wrong units", "\"mm\""});
     }},
    {"DuplicateNames",
     [](const TempDir& d) {
         return validate_features(d, features_json(three_with(R"({"name": "a", "vertex": 7, "image": [50, 60]})")),
                                  {"the name 'a' is used by more than one feature"});
     }},
    {"DuplicateVertices",
     [](const TempDir& d) {
         return validate_features(d, features_json(three_with(R"({"name": "c", "vertex": 8, "image": [50, 60]})")),
                                  {"'b' and 'c' both use vertex 8"});
     }},
    {"EqualImagePoints",
     [](const TempDir& d) {
         return validate_features(d, features_json(three_with(R"({"name": "c", "vertex": 7, "image": [30, 40]})")),
                                  {"'b' and 'c' have the same image point"});
     }},
    {"ImagePointOutsideTheImage",
     [](const TempDir& d) {
         return validate_features(d, features_json(three_with(R"({"name": "c", "vertex": 7, "image": [600, 60]})")),
                                  {"feature 'c'", "outside the 512 x 512 image"});
     }},
    {"NegativeImagePoint",
     [](const TempDir& d) {
         return validate_features(d, features_json(three_with(R"({"name": "c", "vertex": 7, "image": [5, -0.5]})")),
                                  {"feature 'c'", "outside the"});
     }},
    {"UvOutsideTheUnitSquare",
     [](const TempDir& d) {
         return validate_features(
             d, features_json(R"({"name": "a", "vertex": 0, "image": [0.1, 0.2]}, {"name": "b", "vertex": 8, "image": [0.3, 0.4]},
                                 {"name": "c", "vertex": 7, "image": [0.5, 1.5]})",
                              R"("units": "uv")"),
             {"feature 'c'", "outside [0, 1] x [0, 1]"});
     }},
    {"NanLiteral",  // JSON has no NaN: the parser must refuse it with a message, not crash
     [](const TempDir& d) {
         return validate_features(d, features_json(three_with(R"({"name": "c", "vertex": 7, "image": [NaN, 60]})")),
                                  {"not valid JSON"});
     }},
    {"NumberBeyondDouble",
     [](const TempDir& d) {
         return validate_features(d, features_json(three_with(R"({"name": "c", "vertex": 7, "image": [1e999, 60]})")),
                                  {"out of range", "1e999"});
     }},
    {"VertexBeyondTheMesh",
     [](const TempDir& d) {
         return validate_features(d, features_json(three_with(R"({"name": "c", "vertex": 5000, "image": [50, 60]})")),
                                  {"feature 'c' uses vertex 5000", "has only 299 vertices", "nefertiti.off"});
     }},
    {"NegativeVertex",
     [](const TempDir& d) {
         return validate_features(d, features_json(three_with(R"({"name": "c", "vertex": -3, "image": [50, 60]})")),
                                  {"feature 'c'", "non-negative integer"});
     }},
    {"FractionalVertex",
     [](const TempDir& d) {
         return validate_features(d, features_json(three_with(R"({"name": "c", "vertex": 2.5, "image": [50, 60]})")),
                                  {"feature 'c'", "integer"});
     }},
    {"VertexAndPointBoth",
     [](const TempDir& d) {
         return validate_features(
             d, features_json(three_with(R"({"name": "c", "vertex": 7, "point": [0, 0, 0], "image": [50, 60]})")),
             {"feature 'c': give exactly one of"});
     }},
    {"PointOffTheSurface",
     [](const TempDir& d) {
         return validate_features(
             d, features_json(three_with(R"({"name": "c", "point": [1000, 1000, 1000], "image": [50, 60]})")),
             {"feature 'c'", "away from the surface", "nefertiti.off"});
     }},
    {"FewerThanThreeBorderFeaturesWithTheBorderGiven",  // --border auto would place the others
     [](const TempDir& d) {
         CliRun run = validate_features(
             d, features_json(R"({"name": "a", "vertex": 0, "image": [1, 2]}, {"name": "b", "vertex": 1, "image": [3, 4]})"),
             {"only 2 feature(s) lie on the mesh border", "at least 3"});
         run.args += " --border given";
         return run;
     }},
    {"LandmarkOnTheImageEdge",  // --border auto cannot put a border around a point on the image's edge
     [](const TempDir& d) {
         return validate_features(
             d, features_json(R"({"name": "a", "vertex": 100, "image": [0, 100]}, {"name": "b", "vertex": 150, "image": [300, 120]},
                                 {"name": "c", "vertex": 116, "image": [200, 300]})"),
             {"feature 'a' lies on the image's edge but not on the mesh border"});
     }},
    {"ImageSizeNotPositive",
     [](const TempDir& d) {
         return validate_features(d, features_json(kThreeFeatures, R"("image_size": [512, 0])"), {"\"image_size\""});
     }},
    {"ImageSizeDiffersFromImage",
     [](const TempDir& d) {
         return validate_features(d, features_json(kThreeFeatures, R"("image_size": [640, 480])"),
                                  {"[640, 480] differs from the size", "512 x 512"});
     }},
    {"NoImageAtAll",  // no --image, no "image", no "image_size"
     [](const TempDir& d) {
         write_file(d / "f.json", features_json(kThreeFeatures, ""));
         return CliRun{"validate " + q(data("meshes/nefertiti.off")) + " " + q(d / "f.json"), d / "f.json", {"no image"}};
     }},
    {"ImageNamedInFeaturesIsMissing",  // "image" is resolved against the features file's folder
     [](const TempDir& d) {
         write_file(d / "f.json", features_json(kThreeFeatures, R"("image": "photo.png")"));
         return CliRun{"validate " + q(data("meshes/nefertiti.off")) + " " + q(d / "f.json"), d / "photo.png",
                    {"no such image file"}};
     }},
    {"FeaturesFileMissing",
     [](const TempDir& d) {
         return CliRun{"validate " + q(data("meshes/nefertiti.off")) + " " + q(d / "none.json"), d / "none.json",
                    {"no such features file"}};
     }},
};

// ---------------------------------------------------------------------------------------------
// Broken images: `validate nefertiti.off features --image IMAGE`.

CliRun validate_image(const TempDir& d, const std::string& name, const std::string& bytes,
                   std::vector<std::string> keywords) {
    write_file(d / "f.json", features_json(kThreeFeatures, ""));
    write_file(d / name, bytes);
    return {"validate " + q(data("meshes/nefertiti.off")) + " " + q(d / "f.json") + " --image " + q(d / name),
            d / name, std::move(keywords)};
}

const Case kImageCases[] = {
    {"EmptyPng", [](const TempDir& d) { return validate_image(d, "i.png", "", {"empty"}); }},
    {"TruncatedPng",  // the header is whole, the pixel data is cut
     [](const TempDir& d) { return validate_image(d, "i.png", image_bytes().substr(0, 2000), {"truncated or corrupt"}); }},
    {"TruncatedPngHeader",
     [](const TempDir& d) { return validate_image(d, "i.png", image_bytes().substr(0, 20), {"header is truncated"}); }},
    {"GarbagePng", [](const TempDir& d) { return validate_image(d, "i.png", garbage(5000, 5), {"not a PNG or JPEG"}); }},
    {"TextFileAsImage", [](const TempDir& d) { return validate_image(d, "i.jpg", "hello\n", {"not a PNG or JPEG"}); }},
    {"MissingImage",
     [](const TempDir& d) {
         write_file(d / "f.json", features_json(kThreeFeatures, ""));
         return CliRun{"validate " + q(data("meshes/nefertiti.off")) + " " + q(d / "f.json") + " --image " + q(d / "no.png"),
                    d / "no.png", {"no such image file"}};
     }},
};

// ---------------------------------------------------------------------------------------------
// Output paths that cannot be written: the run must fail before anything appears.

const Case kOutputCases[] = {
    {"MtlPathIsAFolder",  // out.obj could be written, out.mtl not: neither may appear
     [](const TempDir& d) {
         std::filesystem::create_directory(d / "out.mtl");
         return CliRun{"convert " + q(data("meshes/nefertiti.off")) + " -o " + q(d / "out.obj"), d / "out.mtl", {"folder"}};
     }},
    {"UnknownOutputFormat",
     [](const TempDir& d) {
         return CliRun{"convert " + q(data("meshes/nefertiti.off")) + " -o " + q(d / "out.txt"), d / "out.txt",
                    {"unknown output format"}};
     }},
    {"OutputFolderMissing",
     [](const TempDir& d) {
         return CliRun{"convert " + q(data("meshes/nefertiti.off")) + " -o " + q(d / "no/out.obj"), d / "no/out.obj",
                    {"does not exist"}};
     }},
};

class BadInputCli : public ::testing::TestWithParam<Case> {};

TEST_P(BadInputCli, IsRejected) {
    TempDir dir;
    const CliRun run = GetParam().make(dir);
    expect_rejected(dir, run);
    if (run.keywords.empty()) ADD_FAILURE() << "a case must name the problem it expects";
}

// Issue 12, must-show 5: on every case `validate` refuses, `map` with the same inputs refuses
// with the same exit code and the same message, word for word (both with the default
// --border auto), and writes nothing.
TEST_P(BadInputCli, MapGivesTheVerdictAndMessageOfValidate) {
    TempDir dir;
    const CliRun run = GetParam().make(dir);
    if (run.args.rfind("validate ", 0) != 0) GTEST_SKIP() << "not a validate case";
    const RunResult v = run_ctmap(run.args);
    CliRun as_map = run;
    as_map.args = "map " + run.args.substr(9) + " -o " + q(dir / "out.obj") + " -q";
    const RunResult m = run_ctmap(as_map.args);
    EXPECT_EQ(v.code, kExitBadInput) << v.out;
    EXPECT_EQ(m.code, v.code) << m.out;
    EXPECT_EQ(m.out, v.out);
    for (const char* out : {"out.obj", "out.mtl"}) EXPECT_FALSE(std::filesystem::exists(dir / out)) << out;
}

std::string case_name(const ::testing::TestParamInfo<Case>& info) { return info.param.name; }

INSTANTIATE_TEST_SUITE_P(Mesh, BadInputCli, ::testing::ValuesIn(kMeshCases), case_name);
INSTANTIATE_TEST_SUITE_P(Topology, BadInputCli, ::testing::ValuesIn(kTopologyCases), case_name);
INSTANTIATE_TEST_SUITE_P(Features, BadInputCli, ::testing::ValuesIn(kFeatureCases), case_name);
INSTANTIATE_TEST_SUITE_P(Image, BadInputCli, ::testing::ValuesIn(kImageCases), case_name);
INSTANTIATE_TEST_SUITE_P(Output, BadInputCli, ::testing::ValuesIn(kOutputCases), case_name);

TEST(BadInputCliBasics, TheValidCounterpartsAreAccepted) {
    // The cases above must fail because of what they break, not because the base inputs are bad.
    TempDir d;
    write_file(d / "f.json", features_json(kThreeFeatures));
    RunResult r = run_ctmap("validate " + q(data("meshes/nefertiti.off")) + " " + q(d / "f.json") + " --image " +
                            q(data("images/astronaut.png")));
    EXPECT_EQ(r.code, 0) << r.out;
    write_file(d / "m.off", std::string(kTriangleOff) + "3 0 1 2\n");
    r = run_ctmap("convert " + q(d / "m.off") + " -o " + q(d / "out.glb"));
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(std::filesystem::exists(d / "out.glb"));
    write_file(d / "m.stl", binary_stl({0, 0, 0, 1, 0, 0, 0, 1, 0}));
    r = run_ctmap("info " + q(d / "m.stl"));
    EXPECT_EQ(r.code, 0) << r.out;
    write_file(d / "m.ply", std::string(kPlyHeader) + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    r = run_ctmap("convert " + q(d / "m.ply") + " -o " + q(d / "out.obj"));
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_TRUE(std::filesystem::exists(d / "out.mtl"));
}

TEST(BadInputCliBasics, UnknownCommandAndMissingArgumentsExitTwo) {
    EXPECT_EQ(run_ctmap("frobnicate").code, kExitBadInput);
    EXPECT_EQ(run_ctmap("validate").code, kExitBadInput);
    EXPECT_EQ(run_ctmap("convert " + q(data("meshes/nefertiti.off"))).code, kExitBadInput);  // no -o
}

}  // namespace
}  // namespace ctmap::test

// `ctmap bake`'s bad inputs (issue 42 must-show 6), through the real program: exit 2, the file
// named with the problem, no texture, mask or OBJ left behind, and the inputs unchanged.
// (The names hold "BadInput": scripts/test.sh runs them again under the sanitizers.)
#include <filesystem>

#include "ctmap/io/image.h"
#include "bad_input_support.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

/// A valid map in `dir`: a unit square in two triangles with UVs, its MTL naming photo.png.
void write_square_map(const TempDir& dir) {
    write_file((dir / "map.obj"),
               "mtllib map.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl m\n"
               "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
    write_file((dir / "map.mtl"), "newmtl m\nmap_Kd photo.png\n");
    Image photo;
    photo.width = photo.height = 8, photo.channels = 4;
    photo.pixels.assign(8 * 8 * 4, 200);
    write_png(photo, (dir / "photo.png"));
}

/// ONTO: the same square with the UVs `vt` (four lines' worth) and faces `f`.
std::string onto_obj(const std::string& vt, const std::string& f = "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n") {
    return "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n" + vt + f;
}

const Case kBakeCases[] = {
    {"OntoWithoutUVs",
     [](const TempDir& d) {
         write_square_map(d);
         write_file((d / "onto.off"), "OFF\n4 2 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n");
         return CliRun{"bake " + q((d / "map.obj")) + " " + q((d / "onto.off")) + " -o " +
                           q((d / "baked.png")),
                       "onto.off", {"no texture coordinates"}};
     }},
    {"OntoUVsAcrossATile",
     [](const TempDir& d) {
         write_square_map(d);
         write_file((d / "onto.obj"), onto_obj("vt 0.5 0.5\nvt 1.5 0.5\nvt 1.5 0.9\nvt 0.5 0.9\n"));
         return CliRun{"bake " + q((d / "map.obj")) + " " + q((d / "onto.obj")) + " -o " +
                           q((d / "baked.png")),
                       "onto.obj", {"cross a UV tile border", "UDIM"}};
     }},
    {"OntoUVsInNoUdimTile",
     [](const TempDir& d) {
         write_square_map(d);
         write_file((d / "onto.obj"), onto_obj("vt -0.9 0.1\nvt -0.1 0.1\nvt -0.1 0.9\nvt -0.9 0.9\n"));
         return CliRun{"bake " + q((d / "map.obj")) + " " + q((d / "onto.obj")) + " -o " +
                           q((d / "baked.png")),
                       "onto.obj", {"outside [0, 1]", "no UDIM tile"}};
     }},
    {"OntoDegenerateUVTriangle",
     [](const TempDir& d) {
         write_square_map(d);
         write_file((d / "onto.obj"), onto_obj("vt 0.1 0.1\nvt 0.5 0.5\nvt 0.9 0.9\nvt 0.1 0.9\n"));
         return CliRun{"bake " + q((d / "map.obj")) + " " + q((d / "onto.obj")) + " -o " +
                           q((d / "baked.png")),
                       "onto.obj", {"face 1", "degenerate UV triangle"}};
     }},
    {"MapWithoutUVs",
     [](const TempDir& d) {
         write_square_map(d);
         write_file((d / "plain.obj"), "mtllib map.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n");
         write_file((d / "onto.obj"), onto_obj("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"));
         return CliRun{"bake " + q((d / "plain.obj")) + " " + q((d / "onto.obj")) + " -o " +
                           q((d / "baked.png")),
                       "plain.obj", {"no texture coordinates"}};
     }},
    {"MapWithoutPhoto",
     [](const TempDir& d) {
         write_file((d / "bare.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\n");
         write_file((d / "onto.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nf 1/1 2/2 3/3\n");
         return CliRun{"bake " + q((d / "bare.obj")) + " " + q((d / "onto.obj")) + " -o " +
                           q((d / "baked.png")),
                       "bare.obj", {"no photo", "--image"}};
     }},
    {"ExactTransferOntoAnotherMesh",
     [](const TempDir& d) {
         write_square_map(d);
         write_file((d / "onto.obj"), "v 0 0 0\nv 2 0 0\nv 2 2 0\nv 0 2 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                               "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
         return CliRun{"bake " + q((d / "map.obj")) + " " + q((d / "onto.obj")) + " -o " +
                           q((d / "baked.png")) + " --transfer exact",
                       "onto.obj", {"not the mesh the map was computed from", "cannot be exact"}};
     }},
    {"ObjOutputOverOnto",
     [](const TempDir& d) {
         write_square_map(d);
         write_file((d / "onto.obj"), onto_obj("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"));
         return CliRun{"bake " + q((d / "map.obj")) + " " + q((d / "onto.obj")) + " -o " +
                           q((d / "baked.png")) + " --obj " + q((d / "onto.obj")),
                       "onto.obj", {"never writes over its inputs"}};
     }},
    {"OntoUvSetOnAnObj",
     [](const TempDir& d) {
         write_square_map(d);
         write_file((d / "onto.obj"), onto_obj("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"));
         return CliRun{"bake " + q((d / "map.obj")) + " " + q((d / "onto.obj")) + " -o " +
                           q((d / "baked.png")) + " --onto-uv TEXCOORD_1",
                       "--onto-uv", {"one UV set"}};
     }},
    {"TextureNotPng",
     [](const TempDir& d) {
         write_square_map(d);
         write_file((d / "onto.obj"), onto_obj("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"));
         return CliRun{"bake " + q((d / "map.obj")) + " " + q((d / "onto.obj")) + " -o " +
                           q((d / "baked.jpg")),
                       "baked.jpg", {"PNG"}};
     }},
    {"MaskOverThePhoto",
     [](const TempDir& d) {
         write_square_map(d);
         write_file((d / "onto.obj"), onto_obj("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"));
         return CliRun{"bake " + q((d / "map.obj")) + " " + q((d / "onto.obj")) + " -o " + q((d / "baked.png")) +
                           " --mask " + q((d / "photo.png")),
                       "photo.png", {"never writes over its inputs"}};
     }},
    {"ObjWhoseMtlIsTheMapsMtl",
     [](const TempDir& d) {
         write_square_map(d);
         std::filesystem::create_directories(d.path() / "sub");
         write_file((d / "map2.obj"), "mtllib sub/m.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                      "usemtl m\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
         write_file((d / "sub/m.mtl"), "newmtl m\nmap_Kd ../photo.png\n");
         write_file((d / "onto.obj"), onto_obj("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"));
         // --obj sub/m.obj would write sub/m.mtl: the map's own material file.
         return CliRun{"bake " + q((d / "map2.obj")) + " " + q((d / "onto.obj")) + " -o " + q((d / "baked.png")) +
                           " --obj " + q((d / "sub/m.obj")),
                       "m.mtl", {"never writes over its inputs"}};
     }},
    {"SameFileForTwoOutputs",
     [](const TempDir& d) {
         write_square_map(d);
         write_file((d / "onto.obj"), onto_obj("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"));
         return CliRun{"bake " + q((d / "map.obj")) + " " + q((d / "onto.obj")) + " -o " + q((d / "baked.png")) +
                           " --mask " + q((d / "baked.png")),
                       "baked.png", {"two outputs"}};
     }},
    {"ChartWithoutAPhoto",
     [](const TempDir& d) {
         write_square_map(d);
         write_file((d / "charts.obj"), "mtllib charts.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                        "usemtl chart_front\nf 1/1 2/2 3/3\nusemtl chart_back\nf 1/1 3/3 4/4\n");
         write_file((d / "charts.mtl"), "newmtl chart_front\nmap_Kd photo.png\nnewmtl chart_back\n");
         write_file((d / "onto.obj"), onto_obj("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"));
         return CliRun{"bake " + q((d / "charts.obj")) + " " + q((d / "onto.obj")) + " -o " + q((d / "baked.png")),
                       "charts.obj", {"chart 1", "chart_back", "names no photo"}};
     }},
};

class BadInputBake : public ::testing::TestWithParam<Case> {};

TEST_P(BadInputBake, IsRejectedWithItsFileNamedAndNothingWritten) {
    TempDir dir;
    const CliRun run = GetParam().make(dir);
    // The inputs as they were: a rejected bake changes none of them.
    std::vector<std::pair<std::string, std::string>> before;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir.path()))
        if (e.is_regular_file()) before.emplace_back(e.path().string(), read_file(e.path().string()));
    expect_rejected(dir, run);
    for (const auto& [path, content] : before) EXPECT_EQ(read_file(path), content) << path << " was changed";
    EXPECT_FALSE(std::filesystem::exists(dir / "baked.png"));
}

TEST(BadInputBakeRobust, SliversAndZeroAreaFacesBakeWithoutACrash) {
    // Review findings: a UV triangle that rounding makes flat in texel coordinates (closest
    // transfer), and an ONTO face with a repeated vertex (zero area in 3D, fine UVs): both bake,
    // exit 0, no crash, no sanitizer report.
    TempDir d;
    write_square_map(d);
    write_file(d / "sliver.obj", "v 0 0 0\nv 1 0 0\nv 0.5 0 0\nvt 0.25 0.25\nvt 0.75 0.25\nvt 0.5 0.25000000000000006\n"
                                 "f 1/1 2/2 3/3\n");
    for (const char* transfer : {"closest", "auto"}) {
        const RunResult r = run_ctmap("bake " + q(d / "map.obj") + " " + q(d / "sliver.obj") + " -o " + q(d / "s.png") +
                                      " --size 2 --transfer " + transfer + " -q");
        EXPECT_EQ(r.code, 0) << r.out;
        EXPECT_EQ(r.out.find("Sanitizer"), std::string::npos) << r.out;
    }
    write_file(d / "repeated.obj", onto_obj("vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvt 0.1 0.9\nvt 0.2 0.9\nvt 0.1 0.95\n",
                                            "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\nf 1/5 1/6 2/7\n"));
    const RunResult r = run_ctmap("bake " + q(d / "map.obj") + " " + q(d / "repeated.obj") + " -o " + q(d / "r.png"));
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_NE(r.out.find("not exact"), std::string::npos) << "a face with no piece of the map makes it not the same mesh: " << r.out;
}

std::string bake_case_name(const ::testing::TestParamInfo<Case>& info) { return info.param.name; }
INSTANTIATE_TEST_SUITE_P(Bake, BadInputBake, ::testing::ValuesIn(kBakeCases), bake_case_name);

}  // namespace
}  // namespace ctmap::test

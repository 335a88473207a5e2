// Issue 17, must-show 1: every input a new user (or a fuzzer) brought that lost a file, crashed,
// hung or gave a wrong answer, through the real `ctmap` program. Each bad input must give exit 2,
// a message naming the file and the problem, the input files byte-identical afterwards, and no
// output left; each good input that used to fail must now give a certified map.
// scripts/test.sh runs these again under ASan + UBSan (`ctest -R BadInput`).
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "ctmap/errors.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

namespace fs = std::filesystem;

/// Runs ctmap under `timeout`, so a hang fails the test (exit 124) instead of blocking the suite.
RunResult run_bounded(const std::string& args, int seconds = 60) {
    return run_ctmap_with_prefix("timeout -k 5 " + std::to_string(seconds), args);
}

/// Every file in `dir` and its bytes.
std::map<std::string, std::string> snapshot(const TempDir& dir) {
    std::map<std::string, std::string> s;
    for (const auto& e : fs::directory_iterator(dir.path()))
        s[e.path().filename().string()] = fs::is_regular_file(e.path()) ? read_file(e.path().string()) : "<not a file>";
    return s;
}

/// The contract of a refused input: exit 2 (not a signal, not a time-out), ctmap's error line
/// naming `file` and saying each keyword, and the folder exactly as before (inputs unchanged,
/// nothing written, no temporary left).
void expect_refused(const TempDir& dir, const std::string& args, const std::string& file,
                    const std::vector<std::string>& keywords) {
    const auto before = snapshot(dir);
    const RunResult r = run_bounded(args);
    SCOPED_TRACE("ctmap " + args + "\n" + r.out);
    EXPECT_EQ(r.code, kExitBadInput);
    EXPECT_EQ(r.out.find("Sanitizer"), std::string::npos);
    EXPECT_EQ(r.out.find("runtime error"), std::string::npos);
    EXPECT_NE(r.out.find("ctmap: error: "), std::string::npos);
    EXPECT_NE(r.out.find(file), std::string::npos) << "the message does not name " << file;
    for (const std::string& k : keywords) EXPECT_NE(r.out.find(k), std::string::npos) << "missing '" << k << "'";
    EXPECT_EQ(snapshot(dir), before) << "a file in the folder was changed, added or removed";
}

/// nefertiti as an OBJ (with its MTL) and the shipped features, copied into `d`.
void copy_example(const TempDir& d) {
    fs::copy_file(data("meshes/nefertiti.off"), d / "in.off");
    fs::copy_file(data("features/nefertiti_astronaut.json"), d / "f.json");
    fs::copy_file(data("images/astronaut.png"), d / "photo.png");
    const RunResult r = run_ctmap("convert " + q(d / "in.off") + " -o " + q(d / "in.obj"));
    ASSERT_EQ(r.code, 0) << r.out;
}

// ---------------------------------------------------------------------------------------------
// Data loss: an output that is an input, or another output.

TEST(BadInputReliability, AnOutputNeverOverwritesAnInput) {
    TempDir d;
    copy_example(d);
    fs::create_symlink(d / "in.obj", d / "link.obj");
    fs::create_hard_link(d / "in.obj", d / "hard.obj");
    fs::create_directory(d / "sub");
    const std::string m = q(d / "in.obj"), f = q(d / "f.json");
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"map " + m + " " + f + " -o " + m, d / "in.obj"},                              // the issue's case
        {"map " + m + " " + f + " -o " + q(d / "sub/../in.obj"), d / "sub/../in.obj"},  // through ..
        {"map " + m + " " + f + " -o " + q(d / "link.obj"), d / "link.obj"},            // a symbolic link
        {"map " + m + " " + f + " -o " + q(d / "hard.obj"), d / "hard.obj"},            // a hard link
        {"map " + m + " " + f + " -o " + q(d / "out.obj") + " --report " + f, d / "f.json"},
        {"map " + m + " " + f + " -o " + q(d / "out.obj") + " --image " + q(d / "photo.png") + " --report " +
             q(d / "photo.png"),
         d / "photo.png"},
        {"convert " + m + " -o " + m, d / "in.obj"},
        {"starter-features " + q(d / "in.off") + " --image " + q(d / "photo.png") + " -o " + q(d / "in.off"), d / "in.off"},
    };
    for (const auto& [args, file] : cases) expect_refused(d, args, file, {"same file as"});
}

TEST(BadInputReliability, TwoOutputsNeverShareAFile) {
    TempDir d;
    copy_example(d);
    const std::string base = "map " + q(d / "in.off") + " " + q(d / "f.json") + " -o " + q(d / "out.obj");
    expect_refused(d, base + " --report " + q(d / "out.obj"), d / "out.obj", {"--report", "the output (-o)"});
    expect_refused(d, base + " --report " + q(d / "out.mtl"), d / "out.mtl", {"--report", "material file"});
    expect_refused(d, base + " --glb " + q(d / "x.glb") + " --report " + q(d / "x.glb"), d / "x.glb", {"--glb"});
}

// ---------------------------------------------------------------------------------------------
// Output problems found before any work: the inputs are not even read.

TEST(BadInputReliability, OutputProblemsAreFoundBeforeTheWork) {
    TempDir d;
    copy_example(d);
    write_file(d / "broken.off", "OFF\n3 1 0\n0 0 0\n");  // would be refused too, but later
    fs::create_directory(d / "folder.obj");
    const std::string in = q(d / "broken.off") + " " + q(d / "f.json");
    expect_refused(d, "map " + in + " -o " + q(d / "none/out.obj"), d / "none/out.obj", {"does not exist"});
    expect_refused(d, "map " + in + " -o " + q(d / "folder.obj"), d / "folder.obj", {"folder"});
    // A folder no file can be created in (root may write anywhere else, but not in /proc).
    expect_refused(d, "map " + in + " -o /proc/ctmap_out.obj", "/proc/ctmap_out.obj", {"cannot create a file"});
    expect_refused(d, "render " + q(d / "in.obj") + " -o /proc/ctmap_out.png", "/proc/ctmap_out.png",
                   {"cannot create a file"});
}

TEST(BadInputReliability, TemporariesOfAKilledRunAreRemovedByTheNextRun) {
    TempDir d;
    copy_example(d);
    // What a run killed by SIGKILL leaves: a temporary named after a process that is gone.
    pid_t dead = 0;
    for (pid_t p = 4000000; p > 3000000; --p)
        if (::kill(p, 0) != 0 && errno == ESRCH) {
            dead = p;
            break;
        }
    ASSERT_GT(dead, 0);
    const std::string stale = d / (".out.obj.tmp" + std::to_string(dead) + "_0");
    const std::string live = d / (".out.obj.tmp" + std::to_string(::getpid()) + "_0");  // this test is alive
    write_file(stale, "partial");
    write_file(live, "being written");
    const RunResult r = run_ctmap("map " + q(d / "in.off") + " " + q(d / "f.json") + " -o " + q(d / "out.obj") + " -q");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_FALSE(fs::exists(stale)) << "the stale temporary is still there";
    EXPECT_TRUE(fs::exists(live)) << "a live run's temporary was removed";
}

// ---------------------------------------------------------------------------------------------
// Inputs that block or never end: pipes, devices, huge declared counts, large polygons.

TEST(BadInputReliability, PipesAndDevicesAreRefusedWithoutBlocking) {
    TempDir d;
    copy_example(d);
    ASSERT_EQ(::mkfifo((d / "pipe.off").c_str(), 0600), 0);
    ASSERT_EQ(::mkfifo((d / "pipe.png").c_str(), 0600), 0);
    ASSERT_EQ(::mkfifo((d / "pipe.json").c_str(), 0600), 0);
    expect_refused(d, "info " + q(d / "pipe.off"), d / "pipe.off", {"not a regular file"});
    expect_refused(d, "validate " + q(d / "in.off") + " " + q(d / "pipe.json"), d / "pipe.json", {"not a regular file"});
    expect_refused(d, "validate " + q(d / "in.off") + " " + q(d / "f.json") + " --image " + q(d / "pipe.png"),
                   d / "pipe.png", {"not a regular file"});
    expect_refused(d, "check " + q(d / "pipe.off") + " --features " + q(d / "f.json"), d / "pipe.off",
                   {"not a regular file"});
    expect_refused(d, "info /dev/zero", "/dev/zero", {"not a regular file"});
}

TEST(BadInputReliability, DeclaredCountsAreCheckedAgainstTheFileSize) {
    TempDir d;
    const std::string ply = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    write_file(d / "corners.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2000000000 0 1 2\n");
    write_file(d / "vertices.ply",
               "ply\nformat ascii 1.0\nelement vertex 3000000000\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    write_file(d / "list.ply", ply + "element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
                                   "0 0 0\n1 0 0\n0 1 0\n200 0 1 2\n");
    std::string binary = "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                         "property float z\nelement face 1\nproperty list uint int vertex_indices\nend_header\n";
    binary += std::string(36, '\0') + std::string("\xff\xff\xff\x7f", 4) + std::string(12, '\0');
    write_file(d / "binary.ply", binary);
    std::string off_binary = std::string("OFF BINARY\n") + std::string(3, '\0') + "\x03" + std::string(3, '\0') + "\x01" +
                             std::string(4, '\0') + std::string(36, '\0') + "\x7f\xff\xff\xff" + std::string(12, '\0');
    write_file(d / "binary.off", off_binary);
    write_file(d / "property_first.ply", "ply\nformat ascii 1.0\nproperty float x\nelement vertex 3\nend_header\n0\n0\n0\n");
    // A list count that is not an integer: CGAL read "-1.3" as 4294967295 values (2 GB; fuzz_ply-7).
    write_file(d / "real_count.ply", ply + "element face 1\nproperty list uint32 int vertex_indices\nend_header\n" +
                                         "0 0 0\n1 0 0\n0 1 0\n-1.3 0 1 2\n");
    expect_refused(d, "info " + q(d / "real_count.ply"), d / "real_count.ply",
                   {"face 0: the count of its list 'vertex_indices' is '-1.3', not a non-negative integer"});
    expect_refused(d, "info " + q(d / "corners.off"), d / "corners.off", {"face 0", "2000000000"});
    expect_refused(d, "info " + q(d / "vertices.ply"), d / "vertices.ply", {"3000000000 vertex elements"});
    expect_refused(d, "info " + q(d / "list.ply"), d / "list.ply", {"face 0 declares a list of 200 values"});
    expect_refused(d, "info " + q(d / "binary.ply"), d / "binary.ply", {"a list of 2147483647 values"});
    expect_refused(d, "info " + q(d / "binary.off"), d / "binary.off", {"face 0 declares 2147483647 corners"});
    expect_refused(d, "info " + q(d / "property_first.ply"), d / "property_first.ply",
                   {"line 3", "'property' line before any 'element'"});
}

// Names, types and tokens of a corrupt mesh header are quoted in the message with every byte
// outside printable ASCII shown as '?' and cut after 64 bytes: a terminal escape sequence in a
// PLY element's name or an OFF keyword does not reach the user's terminal, nor does a megabyte
// token. Each case reaches a different message of the PLY and OFF checks.
TEST(BadInputReliability, HeaderNamesAreQuotedPrintableAndShort) {
    TempDir d;
    const std::string esc = "\x1b[2J";  // "clear the screen"
    const std::string xyz = "property float x\nproperty float y\nproperty float z\n";
    const std::string head = "ply\nformat ascii 1.0\n", bin = "ply\nformat binary_little_endian 1.0\n";
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"count.ply", head + "element v" + esc + " 3000000000\n" + xyz + "end_header\n0 0 0\n"},
        {"empty.ply", head + "element e" + esc + " 100000\nend_header\n"},
        {"type.ply", head + "element vertex 3\nproperty fl" + esc + " x\nend_header\n0\n0\n0\n"},
        {"list_type.ply", head + "element face 1\nproperty list uc" + esc + " int vertex_indices\nend_header\n3 0 1 2\n"},
        {"list.ply", head + "element f" + esc + " 1\nproperty list uchar int idx\nend_header\n200 0 1 2\n"},
        {"count_token.ply", head + "element f" + esc + " 1\nproperty list uchar int i" + esc + "\nend_header\n" +
                                "1" + esc + " 0\n"},
        {"binary.ply", bin + "element v" + esc + " 1000\n" + xyz + "end_header\n" + std::string(12, '\0')},
        {"binary_list.ply", bin + "element f" + esc + " 2\nproperty list uchar int idx\nend_header\n\x01" + std::string(4, '\0')},
        {"keyword.off", esc + "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"},
        {"number.off", "OFF\n3 1 0\n0 0 " + std::string(100000, 'x') + esc + "\n1 0 0\n0 1 0\n3 0 1 2\n"},
    };
    const std::map<std::string, std::string> expected = {
        {"count.ply", "3000000000 v?[2J elements"},
        {"empty.ply", "'e?[2J' elements with no properties"},
        {"type.ply", "unknown property type 'fl?[2J'"},
        {"list_type.ply", "unknown list types 'uc?[2J' 'int'"},
        {"list.ply", "f?[2J 0 declares a list of 200 values"},
        {"count_token.ply", "f?[2J 0: the count of its list 'i?[2J' is '1?[2J'"},
        {"binary.ply", "1000 v?[2J elements"},
        {"binary_list.ply", "truncated in f?[2J 1"},
        {"keyword.off", "the keyword '?[2JOFF' is not supported"},
        {"number.off", "'" + std::string(64, 'x') + "...' is not a number"},
    };
    for (const auto& [name, bytes] : cases) write_file(d / name, bytes);
    for (const auto& [name, bytes] : cases) {
        SCOPED_TRACE(name);
        expect_refused(d, "info " + q(d / name), d / name, {expected.at(name)});
        const RunResult r = run_bounded("info " + q(d / name));
        for (char c : r.out) ASSERT_TRUE(c == '\n' || (c >= 0x20 && c <= 0x7e)) << "byte " << int(c) << " in " << r.out;
        EXPECT_LT(r.out.size(), 1000u);
    }
}

// A feature's name is any JSON string: one that holds a terminal escape sequence (two features
// of that name) is quoted printable in the message too.
TEST(BadInputReliability, FeatureNamesAreQuotedPrintable) {
    TempDir d;
    copy_example(d);
    write_file(d / "esc.json", "{\"units\": \"uv\", \"features\": ["
                               "{\"name\": \"\\u001b[2J\", \"vertex\": 0, \"image\": [0.2, 0.2]},"
                               "{\"name\": \"\\u001b[2J\", \"vertex\": 8, \"image\": [0.8, 0.2]},"
                               "{\"name\": \"c\", \"vertex\": 7, \"image\": [0.5, 0.8]}]}");
    const std::string args = "validate " + q(d / "in.off") + " " + q(d / "esc.json");
    expect_refused(d, args, d / "esc.json", {"the name '?[2J' is used by more than one feature"});
    const RunResult r = run_bounded(args);
    for (char c : r.out) ASSERT_TRUE(c == '\n' || (c >= 0x20 && c <= 0x7e)) << "byte " << int(c) << " in " << r.out;
    // Valid UTF-8 stays readable.
    write_file(d / "utf8.json", "{\"units\": \"uv\", \"features\": ["
                                "{\"name\": \"\u0153il\", \"vertex\": 0, \"image\": [0.2, 0.2]},"
                                "{\"name\": \"\u0153il\", \"vertex\": 8, \"image\": [0.8, 0.2]},"
                                "{\"name\": \"c\", \"vertex\": 7, \"image\": [0.5, 0.8]}]}");
    expect_refused(d, "validate " + q(d / "in.off") + " " + q(d / "utf8.json"), d / "utf8.json",
                   {"the name '\xc5\x93il' is used by more than one feature"});
    // A file name from the features file (its image) is printed through the same filter: the
    // command line's last word on every message.
    write_file(d / "image.json", "{\"image\": \"\\u001b[2J.png\", \"features\": ["
                                 "{\"name\": \"a\", \"vertex\": 0, \"image\": [20, 20]},"
                                 "{\"name\": \"b\", \"vertex\": 8, \"image\": [80, 20]},"
                                 "{\"name\": \"c\", \"vertex\": 7, \"image\": [50, 80]}]}");
    const RunResult ri = run_bounded("validate " + q(d / "in.off") + " " + q(d / "image.json"));
    EXPECT_EQ(ri.code, kExitBadInput) << ri.out;
    EXPECT_NE(ri.out.find("?[2J.png"), std::string::npos) << ri.out;
    for (char c : ri.out) ASSERT_TRUE(c == '\n' || (c >= 0x20 && c <= 0x7e)) << "byte " << int(c) << " in " << ri.out;
}

/// An OFF file of one polygon with `n` corners at `corner(i)`.
std::string polygon_off(int n, const std::function<Vec3(int)>& corner) {
    std::ostringstream os;
    os.precision(17);
    os << "OFF\n" << n << " 1 0\n";
    for (int i = 0; i < n; ++i) {
        const Vec3 p = corner(i);
        os << p.x() << " " << p.y() << " " << p.z() << "\n";
    }
    os << n;
    for (int i = 0; i < n; ++i) os << " " << i;
    os << "\n";
    return os.str();
}

TEST(BadInputReliability, LargePolygonsAreTriangulatedOrRefusedInBoundedTime) {
    TempDir d;
    // A random non-planar 1,600-corner polygon took CGAL's hole filling 8 s and 700 MB (cubic).
    std::mt19937 g(7);
    std::uniform_real_distribution<double> u(0, 1);
    write_file(d / "random.off", polygon_off(1600, [&](int) { return Vec3(u(g), u(g), u(g)); }));
    expect_refused(d, "info " + q(d / "random.off"), d / "random.off", {"1600 corners", "could not be triangulated"});
    // A 3,000-corner cap of a cylinder, slightly wavy, is a real n-gon: triangulated, n - 2 triangles.
    const int n = 3000;
    write_file(d / "cap.off", polygon_off(n, [&](int i) {
                   const double a = 2 * M_PI * i / n;
                   return Vec3(std::cos(a), std::sin(a), 1e-3 * std::sin(7 * a));
               }));
    const TriMesh cap = read_mesh(d / "cap.off");
    EXPECT_EQ(cap.num_faces(), n - 2);
    for (const Tri& t : cap.faces) {  // oriented like the polygon (counter-clockwise seen from +z)
        const Vec3 nrm = (cap.positions[t[1]] - cap.positions[t[0]]).cross(cap.positions[t[2]] - cap.positions[t[0]]);
        EXPECT_GT(nrm.z(), 0);
    }
}

TEST(BadInputReliability, DeeplyNestedJsonIsRefusedBeforeParsing) {
    TempDir d;
    copy_example(d);
    write_file(d / "deep.json", std::string(100000, '[') + std::string(100000, ']'));
    write_file(d / "deep2.json", "{\"features\": " + std::string(10000, '[') + std::string(10000, ']') + "}");
    expect_refused(d, "validate " + q(d / "in.off") + " " + q(d / "deep.json"), d / "deep.json", {"nested more than 64"});
    expect_refused(d, "map " + q(d / "in.off") + " " + q(d / "deep2.json") + " -o " + q(d / "out.obj"), d / "deep2.json",
                   {"nested more than 64"});
}

// ---------------------------------------------------------------------------------------------
// Inputs read wrong: a byte-order mark.

TEST(BadInputReliability, AnObjWithAByteOrderMarkLosesNoVertex) {
    TempDir d;
    copy_example(d);
    write_file(d / "bom.obj", "\xEF\xBB\xBF" + read_file(d / "in.obj"));
    const TriMesh plain = read_mesh(d / "in.obj"), bom = read_mesh(d / "bom.obj");
    EXPECT_EQ(bom.num_vertices(), plain.num_vertices());
    EXPECT_EQ(bom.faces, plain.faces);
    EXPECT_EQ(bom.positions, plain.positions);
    const TexturedMesh t = read_textured_obj(d / "bom.obj");
    EXPECT_EQ(t.mesh.positions, plain.positions);
    const RunResult r = run_ctmap("map " + q(d / "bom.obj") + " " + q(d / "f.json") + " -o " + q(d / "out.obj") + " -q");
    EXPECT_EQ(r.code, 0) << r.out;
}

// ---------------------------------------------------------------------------------------------
// Frictions: a mistyped command, help texts, `render -q`, `validate` agreeing with `map`.

TEST(BadInputReliability, AMistypedCommandIsNamedWithTheOneMeant) {
    RunResult r = run_ctmap("mapp x y");
    EXPECT_EQ(r.code, kExitBadInput);
    EXPECT_NE(r.out.find("unknown command 'mapp'; did you mean 'map'?"), std::string::npos) << r.out;
    r = run_ctmap("rendr");
    EXPECT_NE(r.out.find("did you mean 'render'?"), std::string::npos) << r.out;
    r = run_ctmap("frobnicate");
    EXPECT_EQ(r.code, kExitBadInput);
    EXPECT_EQ(r.out.find("did you mean"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("commands: "), std::string::npos) << r.out;
}

TEST(BadInputReliability, HelpTextsNameNoFileTheUserDoesNotHave) {
    for (const char* c : {"", "map", "validate", "check", "render", "info", "convert", "starter-features", "demo"}) {
        const RunResult r = run_ctmap(std::string(c) + " --help");
        EXPECT_EQ(r.code, 0) << c;
        EXPECT_EQ(r.out.find("DESIGN"), std::string::npos) << "ctmap " << c << " --help:\n" << r.out;
    }
}

TEST(BadInputReliability, ValidateGivesTheVerdictAndMessageOfMap) {
    TempDir d;
    copy_example(d);
    // Three layouts `validate` used to pass and `map` refused: no border feature, the border
    // features out of the border's order, an interior feature outside the border polygon.
    const std::string head = R"({"image_size": [512, 512], "features": [)";
    // nefertiti's border runs 0, 1, 2, 3, 4, 8, 5, 6, 7, ..., 298, ...; 100, 116 and 150 are inside.
    write_file(d / "none_on_border.json", head + R"({"name": "a", "vertex": 100, "image": [100, 100]},
        {"name": "b", "vertex": 150, "image": [300, 120]}, {"name": "c", "vertex": 116, "image": [200, 300]}]})");
    write_file(d / "order.json", head + R"({"name": "a", "vertex": 0, "image": [100, 100]},
        {"name": "b", "vertex": 8, "image": [400, 100]}, {"name": "c", "vertex": 7, "image": [100, 400]},
        {"name": "e", "vertex": 298, "image": [400, 400]}]})");
    write_file(d / "outside.json", head + R"({"name": "a", "vertex": 0, "image": [100, 100]},
        {"name": "b", "vertex": 8, "image": [400, 100]}, {"name": "c", "vertex": 7, "image": [400, 400]},
        {"name": "e", "vertex": 298, "image": [100, 400]}, {"name": "i", "vertex": 116, "image": [500, 500]}]})");
    // With --border given (the paper's rules) all three are refused; the default --border auto
    // places border features for the first and the third (tests/test_auto_border.cpp), and must
    // still refuse the second, whose given border features cross.
    for (const char* name : {"none_on_border.json", "order.json", "outside.json"}) {
        const RunResult v = run_ctmap("validate " + q(d / "in.off") + " " + q(d / name) + " --border given");
        const RunResult m =
            run_ctmap("map " + q(d / "in.off") + " " + q(d / name) + " -o " + q(d / "out.obj") + " -q --border given");
        EXPECT_EQ(v.code, kExitBadInput) << name << "\n" << v.out;
        EXPECT_EQ(m.code, kExitBadInput) << name << "\n" << m.out;
        EXPECT_EQ(v.out, m.out) << name;  // the same message, word for word
        EXPECT_NE(v.out.find(d / name), std::string::npos) << v.out;
    }
    {
        const RunResult v = run_ctmap("validate " + q(d / "in.off") + " " + q(d / "order.json"));
        const RunResult m = run_ctmap("map " + q(d / "in.off") + " " + q(d / "order.json") + " -o " + q(d / "out.obj") + " -q");
        EXPECT_EQ(v.code, kExitBadInput) << v.out;
        EXPECT_EQ(v.out, m.out);
        EXPECT_NE(v.out.find("cross in the image"), std::string::npos) << v.out;
    }
    for (const char* name : {"none_on_border.json", "outside.json"}) {
        const RunResult v = run_ctmap("validate " + q(d / "in.off") + " " + q(d / name));
        EXPECT_EQ(v.code, 0) << name << "\n" << v.out;
        EXPECT_NE(v.out.find("`ctmap map` adds"), std::string::npos) << v.out;
        const RunResult m = run_ctmap("map " + q(d / "in.off") + " " + q(d / name) + " -o " + q(d / "out.obj"));
        EXPECT_EQ(m.code, 0) << name << "\n" << m.out;
        EXPECT_NE(m.out.find("border: added"), std::string::npos) << m.out;
        EXPECT_NE(m.out.find("certificate: valid"), std::string::npos) << m.out;
    }
    const RunResult ok = run_ctmap("validate " + q(d / "in.off") + " " + q(d / "f.json"));
    EXPECT_EQ(ok.code, 0) << ok.out;
    EXPECT_NE(ok.out.find("22 patches"), std::string::npos) << ok.out;  // the triangulation `map` cuts along
}

// Named Render*: scripts/test.sh leaves it out of the sanitizer pass (Mesa's llvmpipe "leaks").
TEST(RenderReliability, RenderIsQuietWithQ) {
    TempDir d;
    copy_example(d);
    RunResult r = run_ctmap("map " + q(d / "in.off") + " " + q(d / "f.json") + " -o " + q(d / "m.obj") + " --image " +
                            q(d / "photo.png") + " -q");
    ASSERT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out, "");
    r = run_ctmap("render " + q(d / "m.obj") + " -o " + q(d / "m.png") + " --size 64 -q");
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out, "");
    EXPECT_TRUE(fs::is_regular_file(d / "m.png"));
}

// ---------------------------------------------------------------------------------------------
// The inputs the fuzzers found (fuzz/regressions): through the real program, in this build and
// the sanitizer build, each is refused with exit 2 and no sanitizer report.

TEST(BadInputReliability, WhatTheFuzzersFoundIsRefusedCleanly) {
    TempDir d;
    copy_example(d);
    const fs::path root = fs::path(ctmap_test::source_dir()) / "fuzz" / "regressions";
    ASSERT_TRUE(fs::is_directory(root)) << root;
    int cases = 0;
    for (const auto& target : fs::directory_iterator(root)) {
        const std::string t = target.path().filename().string();
        for (const auto& input : fs::directory_iterator(target.path())) {
            const std::string name = input.path().filename().string();
            std::string file, args;
            if (t == "fuzz_image") {
                file = d / (name + ".png");
                args = "validate " + q(d / "in.off") + " " + q(d / "f.json") + " --image " + q(file);
            } else {
                const std::string ext = t == "fuzz_textured_obj" ? ".obj" : "." + t.substr(5);
                file = d / (name + ext);
                args = t == "fuzz_textured_obj" || t == "fuzz_glb" || t == "fuzz_gltf"
                           ? "check " + q(file) + " --features " + q(d / "f.json")
                           : "info " + q(file);
            }
            fs::copy_file(input.path(), file);
            expect_refused(d, args, file, {});
            fs::remove(file);
            ++cases;
        }
    }
    EXPECT_GE(cases, 13);
}

}  // namespace
}  // namespace ctmap::test

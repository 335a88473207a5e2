// The bad-input suite's library half (issue 2, point 3): the library throws the right type for a
// broken input, BadInput naming the file for broken files, TopologyError (a BadInput) for meshes
// that read but are not discs, and writes all of an output set or none of it. The CLI half is
// test_bad_input.cpp. scripts/test.sh runs both again under AddressSanitizer +
// UndefinedBehaviorSanitizer (`ctest -R BadInput`), so every test name here contains "BadInput".
#include <filesystem>
#include <string>

#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"
#include "ctmap/io/features.h"
#include "ctmap/io/glb_io.h"
#include "ctmap/io/image.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
#include "bad_input_support.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

// ---------------------------------------------------------------------------------------------
// The library throws the right type: BadInput for broken files, TopologyError (a BadInput) for
// meshes that read but are not discs. The CLI maps both to exit 2; later stages catch them apart.

/// Calls `f`, expects it to throw exactly the BadInput family member E, and returns the exception.
template <class E, class F>
E expect_throws(F&& f) {
    try {
        f();
    } catch (const E& e) {
        return e;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "threw the wrong type: " << e.what();
        return E("", "");
    }
    ADD_FAILURE() << "did not throw";
    return E("", "");
}

TEST(BadInputLibrary, BrokenMeshFilesThrowBadInputNotTopologyError) {
    TempDir d;
    write_file(d / "nan.off", "OFF\n3 1 0\n0 0 0\nnan 0 0\n0 1 0\n3 0 1 2\n");
    const BadInput e = expect_throws<BadInput>([&] { read_mesh(d / "nan.off"); });
    EXPECT_EQ(e.file(), d / "nan.off");
    EXPECT_NE(e.problem().find("NaN"), std::string::npos) << e.problem();
    EXPECT_EQ(std::string(e.what()).rfind(d / "nan.off" + ": ", 0), 0u) << "what() starts with the file";
    try {
        read_mesh(d / "nan.off");
    } catch (const TopologyError&) {
        ADD_FAILURE() << "a file that cannot be read is not a topology problem";
    } catch (const BadInput&) {
    }
    write_file(d / "big.off", "OFF\n2000000000 1 0\n0 0 0\n");
    EXPECT_NE(expect_throws<BadInput>([&] { read_mesh(d / "big.off"); }).problem().find("truncated"), std::string::npos);
}

TEST(BadInputLibrary, NonDiscsThrowTopologyError) {
    TempDir d;
    write_file(d / "bow.off", "OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n-1 0 0\n0 -1 0\n3 0 1 2\n3 0 3 4\n");
    const TriMesh bow = read_mesh(d / "bow.off");  // reads fine: the file is well formed
    const TopologyError e = expect_throws<TopologyError>([&] { require_disc(compute_topology(bow), d / "bow.off"); });
    EXPECT_EQ(e.file(), d / "bow.off");
    EXPECT_NE(e.problem().find("non-manifold vertex"), std::string::npos) << e.problem();
    // The closed cow is a topology problem too, and a disc passes.
    const std::string cow = data("meshes/cow.off");
    EXPECT_NE(expect_throws<TopologyError>([&] { require_disc(compute_topology(read_mesh(cow)), cow); })
                  .problem()
                  .find("closed"),
              std::string::npos);
    const std::string nef = data("meshes/nefertiti.off");
    EXPECT_NO_THROW(require_disc(compute_topology(read_mesh(nef)), nef));
    // The advice depends on the command: map takes charts, serve/morph/Python one chart only.
    const std::string head = data("meshes/head.off");
    const MeshTopology ht = compute_topology(read_mesh(head));
    const std::string with_charts = expect_throws<TopologyError>([&] { require_disc(ht, head); }).problem();
    EXPECT_NE(with_charts.find("give a features file with charts"), std::string::npos) << with_charts;
    const std::string one_chart =
        expect_throws<TopologyError>([&] { require_disc(ht, head, NotDiscAdvice::cut_open); }).problem();
    EXPECT_NE(one_chart.find("3 border loops"), std::string::npos) << one_chart;
    EXPECT_NE(one_chart.find("this command takes one chart: fill the holes"), std::string::npos) << one_chart;
    EXPECT_EQ(one_chart.find("give a features file"), std::string::npos) << one_chart;
}

TEST(BadInputLibrary, FeaturesImagesObjAndOutputsThrowBadInput) {
    TempDir d;
    const BadInput f = expect_throws<BadInput>([&] { parse_features(R"({"features": [1e999]})", "x.json"); });
    EXPECT_EQ(f.file(), "x.json");
    EXPECT_NE(f.problem().find("out of range"), std::string::npos) << f.problem();

    write_file(d / "i.png", read_file(data("images/astronaut.png")).substr(0, 1000));
    EXPECT_NE(expect_throws<BadInput>([&] { read_image(d / "i.png"); }).problem().find("truncated"), std::string::npos);

    write_file(d / "m.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/2\n");
    const BadInput o = expect_throws<BadInput>([&] { read_textured_obj(d / "m.obj"); });
    EXPECT_NE(o.problem().find("line 5: texture coordinate index 2 is out of range"), std::string::npos) << o.problem();

    std::filesystem::create_directory(d / "taken");
    EXPECT_NE(expect_throws<BadInput>([&] { AtomicFile a(d / "taken"); }).problem().find("folder"), std::string::npos);
}

/// `v` as a GLB stores it: 4 bytes, little-endian.
std::string word(std::uint32_t v) {
    std::string w(4, '\0');
    for (int k = 0; k < 4; ++k) w[k] = char((v >> (8 * k)) & 0xff);
    return w;
}

/// A GLB: the 12-byte header with its length (plus `length_delta`), a JSON chunk holding `json`
/// (padded to 4 bytes), then `tail` as it is (a BIN chunk's header and data, or part of one).
std::string glb_bytes(const std::string& json, const std::string& tail, long length_delta = 0) {
    std::string j = json;
    while (j.size() % 4) j += ' ';
    const std::uint32_t length = std::uint32_t(long(12 + 8 + j.size() + tail.size()) + length_delta);
    return "glTF" + word(2) + word(length) + word(std::uint32_t(j.size())) + "JSON" + j + tail;
}

TEST(BadInputLibrary, AGlbWhoseChunksRunPastItsEndIsRefusedBeforeItIsParsed) {
    // fuzz/regressions/fuzz_glb/fuzz_glb-2: a BIN chunk that claims up to 8 bytes more than the
    // file holds was read past the end of the buffer by tinygltf 2.7.0 (its bound leaves out the
    // chunk's own header). Each layout here must be a BadInput naming the file and the chunk.
    TempDir d;
    const std::string json = R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":8}]})";
    const struct {
        const char* name;
        std::string bytes;
        const char* says;
    } cases[] = {
        {"bin4.glb", glb_bytes(json, word(8) + "BIN" + std::string(1, '\0') + std::string(4, 'x')), "BIN chunk runs past"},
        {"bin1.glb", glb_bytes(json, word(8) + "BIN" + std::string(1, '\0') + std::string(7, 'x')), "BIN chunk runs past"},
        {"head.glb", glb_bytes(json, word(8)), "BIN chunk header runs past"},
        {"long.glb", glb_bytes(json, "", 4), "the file has"},
        {"json.glb", "glTF" + word(2) + word(24) + word(64) + "JSON" + "{}  ", "JSON chunk runs past"},
        {"v1.glb", "glTF" + word(1) + word(24) + word(4) + "JSON" + "{}  ", "version 1"},
    };
    for (const auto& c : cases) {
        SCOPED_TRACE(c.name);
        write_file(d / c.name, c.bytes);
        const BadInput e = expect_throws<BadInput>([&] { read_glb(d / c.name); });
        EXPECT_EQ(e.file(), d / c.name);
        EXPECT_NE(e.problem().find(c.says), std::string::npos) << e.problem();
    }
    // The same layout with the chunk whole is past the container check (and then has no mesh).
    write_file(d / "whole.glb", glb_bytes(json, word(8) + "BIN" + std::string(1, '\0') + std::string(8, 'x')));
    const BadInput whole = expect_throws<BadInput>([&] { read_glb(d / "whole.glb"); });
    EXPECT_NE(whole.problem().find("no mesh"), std::string::npos) << whole.problem();
}

TEST(BadInputLibrary, OutputSetIsAllOrNothing) {
    // Two outputs; the second cannot be renamed into place (its target became a folder after the
    // set was made): the first must be taken back, and both temporaries removed.
    TempDir d;
    {
        OutputSet set;
        const std::string a = set.add(d / "a.txt");
        const std::string b = set.add(d / "b.txt");
        write_file(a, "first");
        write_file(b, "second");
        std::filesystem::create_directory(d / "b.txt");
        write_file(d / "b.txt/keep", "x");  // a non-empty folder cannot be replaced by rename
        EXPECT_THROW(set.commit_all(), InternalError);
        EXPECT_FALSE(std::filesystem::exists(d / "a.txt"));
    }
    EXPECT_EQ(d.count(), 1) << "only the folder b.txt remains; temporaries are gone";
}

}  // namespace
}  // namespace ctmap::test

// border_loop (the border of a disc straight from the faces) against the tests' own set-based
// loop, on every real disc mesh and on a subdivided one.
#include <gtest/gtest.h>

#include "ctmap/border_loop.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/subdivide.h"
#include "map_cases.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

TEST(BorderLoop, AgreesWithTheSetBasedLoop) {
    for (const char* name : {"nefertiti.off", "mushroom.off", "three_peaks.off", "lion-head.off", "mannequin-devil.off"}) {
        const TriMesh mesh = read_mesh(data(std::string("meshes/") + name));
        const std::vector<int> loop = ctmap::border_loop(mesh);
        EXPECT_GE(loop.size(), 3u) << name;
        EXPECT_EQ(loop, border_loop_by_sets(mesh)) << name;
    }
    const TriMesh fine = subdivide_midpoint(read_mesh(data("meshes/nefertiti.off")), 2);
    EXPECT_EQ(ctmap::border_loop(fine), border_loop_by_sets(fine));
}

TEST(BorderLoop, ClosedMeshHasNone) {
    TriMesh tetra;
    tetra.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    tetra.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {2, 0, 3}};
    EXPECT_TRUE(ctmap::border_loop(tetra).empty());
}

}  // namespace
}  // namespace ctmap::test

// Seams off the handles (cut/seam_homology.h): the handle loops of a closed mesh tell a loop that
// splits the mesh from one that goes round a handle, checked on a torus whose loops are known by
// construction, and the shortest path of a class is simple and of that class.
#include <gtest/gtest.h>

#include <cmath>

#include "ctmap/cut/seam_homology.h"
#include "ctmap/io/read_mesh.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

constexpr int kRing = 12, kTube = 8;  // vertices round the torus, round its tube

int torus_vertex(int i, int j) { return ((i + kRing) % kRing) * kTube + (j + kTube) % kTube; }

/// A torus of kRing x kTube vertices, consistently oriented.
TriMesh torus() {
    TriMesh m;
    for (int i = 0; i < kRing; ++i)
        for (int j = 0; j < kTube; ++j) {
            const double u = 2 * M_PI * i / kRing, v = 2 * M_PI * j / kTube;
            m.positions.push_back(Vec3((3 + std::cos(v)) * std::cos(u), (3 + std::cos(v)) * std::sin(u), std::sin(v)));
        }
    for (int i = 0; i < kRing; ++i)
        for (int j = 0; j < kTube; ++j) {
            const int a = torus_vertex(i, j), b = torus_vertex(i + 1, j), c = torus_vertex(i + 1, j + 1), d = torus_vertex(i, j + 1);
            m.faces.push_back({a, b, c});
            m.faces.push_back({a, c, d});
        }
    return m;
}

TEST(SeamHomology, TorusLoopsRoundTheHandleAreTold) {
    const TriMesh m = torus();
    const SeamGraph graph(m);
    const HandleLoops loops = handle_loops(m, graph);
    ASSERT_EQ(loops.count, 2);  // genus 1
    std::vector<int> meridian, longitude, diagonal;
    for (int j = 0; j < kTube; ++j) meridian.push_back(torus_vertex(0, j));
    for (int i = 0; i < kRing; ++i) longitude.push_back(torus_vertex(i, 0));
    const std::uint32_t pm = loops.parity(meridian, true), pl = loops.parity(longitude, true);
    EXPECT_NE(pm, 0u) << "a meridian does not split the torus";
    EXPECT_NE(pl, 0u) << "a longitude does not split the torus";
    EXPECT_NE(pm, pl) << "meridian and longitude are different classes";
    // Another meridian is the same class; every face's border and a loop round four faces split it.
    std::vector<int> other;
    for (int j = 0; j < kTube; ++j) other.push_back(torus_vertex(5, j));
    EXPECT_EQ(loops.parity(other, true), pm);
    for (const Tri& t : m.faces) EXPECT_EQ(loops.parity({t[0], t[1], t[2]}, true), 0u);
    const std::vector<int> square{torus_vertex(2, 2), torus_vertex(3, 2), torus_vertex(4, 2), torus_vertex(4, 3),
                                  torus_vertex(4, 4), torus_vertex(3, 4), torus_vertex(2, 4), torus_vertex(2, 3)};
    EXPECT_EQ(loops.parity(square, true), 0u);
}

TEST(SeamHomology, ClosedSphereAndBorderedMeshesHaveNoHandleLoops) {
    for (const char* name : {"meshes/cow.off", "meshes/holes.off"}) {
        const TriMesh m = read_mesh(data(name));
        EXPECT_EQ(handle_loops(m, SeamGraph(m)).count, 0) << name;
    }
    const TriMesh elk = read_mesh(data("meshes/elk.off"));
    EXPECT_EQ(handle_loops(elk, SeamGraph(elk)).count, 2) << "elk has one handle";
}

TEST(SeamHomology, ShortestPathOfEachClassIsSimpleAndOfThatClass) {
    const TriMesh m = torus();
    const SeamGraph graph(m);
    const HandleLoops loops = handle_loops(m, graph);
    const int a = torus_vertex(0, 0), b = torus_vertex(3, 1);
    std::vector<char> blocked(m.num_vertices(), 0);
    blocked[a] = blocked[b] = 1;
    auto length = [&](const std::vector<int>& p) {
        double l = 0;
        for (std::size_t i = 0; i + 1 < p.size(); ++i) l += (m.positions[p[i + 1]] - m.positions[p[i]]).norm();
        return l;
    };
    const std::vector<int> plain = seam_shortest_path(m, graph, a, b, blocked, {});
    ASSERT_FALSE(plain.empty());
    int found = 0;
    for (std::uint32_t parity = 0; parity < 4; ++parity) {
        const std::vector<int> p = seam_path_of_parity(m, graph, loops, a, b, parity, blocked, {}, nullptr);
        if (p.empty()) continue;
        ++found;
        EXPECT_EQ(p.front(), a);
        EXPECT_EQ(p.back(), b);
        EXPECT_EQ(loops.parity(p, false), parity);
        std::vector<int> sorted = p;
        std::sort(sorted.begin(), sorted.end());
        EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end()) << "not simple";
        for (std::size_t i = 0; i + 1 < p.size(); ++i) EXPECT_TRUE(graph.left(p[i], p[i + 1]) >= 0 || graph.left(p[i + 1], p[i]) >= 0);
        if (parity == loops.parity(plain, false)) EXPECT_NEAR(length(p), length(plain), 1e-9) << "the plain shortest path's class";
        else EXPECT_GT(length(p), length(plain) - 1e-9);
    }
    EXPECT_EQ(found, 4) << "on a torus, a simple path of every class joins two vertices";
}

}  // namespace
}  // namespace ctmap::test

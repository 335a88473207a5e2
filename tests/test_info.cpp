// `ctmap info`: topology of every shipped mesh against facts known independently of ctmap
// (DATA README: counts from CGAL's data set; a disc has Euler characteristic 1, a sphere 2).
#include <nlohmann/json.hpp>

#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/read_mesh.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

struct Expected {
    const char* file;
    int vertices, faces;
    bool disc, closed;
};

/// Readable test names in ctest and failure reports, instead of the struct's raw bytes.
void PrintTo(const Expected& e, std::ostream* os) {
    *os << e.file << " (" << e.vertices << " vertices, " << e.faces << " faces"
        << (e.disc ? ", disc" : "") << (e.closed ? ", closed" : "") << ")";
}

class InfoOnRealMeshes : public ::testing::TestWithParam<Expected> {};

TEST_P(InfoOnRealMeshes, CountsMatchTheDataSheet) {
    const Expected e = GetParam();
    const std::string path = data(std::string("meshes/") + e.file);
    const RunResult r = run_ctmap("info --json " + q(path));
    ASSERT_EQ(r.code, 0) << r.out;
    const auto j = nlohmann::json::parse(r.out);
    EXPECT_EQ(j["vertices"], e.vertices);
    EXPECT_EQ(j["faces"], e.faces);
    EXPECT_EQ(j["is_disc"], e.disc);
    EXPECT_EQ(j["is_closed"], e.closed);
    EXPECT_EQ(j["components"], 1);
    EXPECT_EQ(j["non_manifold_vertices"], 0);
    EXPECT_EQ(j["non_manifold_edges"], 0);
    // Euler's formula with the edge count of a manifold triangle mesh: 2E = 3F + border edges.
    EXPECT_EQ(2 * j["edges"].get<int>(), 3 * e.faces + j["border_edges"].get<int>());
    if (e.disc) {
        EXPECT_EQ(j["border_loops"], 1);
        EXPECT_EQ(j["euler"], 1);
    }
    if (e.closed) {
        EXPECT_EQ(j["border_loops"], 0);
        EXPECT_EQ(j["euler"], 2);
    }
}

INSTANTIATE_TEST_SUITE_P(Data, InfoOnRealMeshes,
                         ::testing::Values(Expected{"nefertiti.off", 299, 562, true, false},
                                           Expected{"mannequin-devil.off", 12977, 25888, true, false},
                                           Expected{"lion-head.off", 8356, 16674, true, false},
                                           Expected{"mushroom.off", 2337, 4608, true, false},
                                           Expected{"three_peaks.off", 1907, 3671, true, false},
                                           Expected{"cow.off", 2904, 5804, false, true}),
                         [](const auto& info) {
                             std::string n = info.param.file;
                             for (char& c : n)
                                 if (!std::isalnum((unsigned char)c)) c = '_';
                             return n;
                         });

TEST(Topology, HandMadeCases) {
    // Two triangles sharing one vertex only: a bow-tie, one non-manifold vertex.
    TriMesh bow;
    bow.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}, {0, -1, 0}};
    bow.faces = {{0, 1, 2}, {0, 3, 4}};
    MeshTopology t = compute_topology(bow);
    EXPECT_EQ(t.non_manifold_vertices, 1);
    EXPECT_EQ(t.non_manifold_edges, 0);
    EXPECT_FALSE(t.is_disc);

    // Three triangles on one edge.
    TriMesh fin;
    fin.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
    fin.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    t = compute_topology(fin);
    EXPECT_EQ(t.non_manifold_edges, 1);
    EXPECT_FALSE(t.is_manifold);

    // A quad split in two, one face flipped: inconsistent orientation.
    TriMesh quad;
    quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    quad.faces = {{0, 1, 2}, {0, 2, 3}};
    t = compute_topology(quad);
    EXPECT_TRUE(t.is_disc);
    EXPECT_EQ(t.border_loops, 1);
    EXPECT_EQ(t.euler, 1);
    quad.faces[1] = {0, 3, 2};
    t = compute_topology(quad);
    EXPECT_EQ(t.inconsistent_edges, 1);
    EXPECT_FALSE(t.is_disc);

    // Collinear corners and a repeated vertex position.
    TriMesh deg;
    deg.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 0}};
    deg.faces = {{0, 1, 2}, {3, 1, 2}};
    t = compute_topology(deg);
    EXPECT_EQ(t.degenerate_faces, 2);
    EXPECT_EQ(t.duplicated_vertices, 1);
}

TEST(ReadMesh, PolygonsAreTriangulatedAndOrderIsKept) {
    TempDir dir;
    // A planar, non-convex hexagon (an L shape) and a quad, in OFF.
    write_file(dir / "poly.off",
               "OFF\n8 2 0\n0 0 0\n2 0 0\n2 1 0\n1 1 0\n1 2 0\n0 2 0\n3 0 0\n3 1 0\n6 0 1 2 3 4 5\n4 1 6 7 2\n");
    const TriMesh m = read_mesh(dir / "poly.off");
    ASSERT_EQ(m.num_vertices(), 8);
    EXPECT_EQ(m.positions[4], Vec3(1, 2, 0));  // input order kept
    ASSERT_EQ(m.num_faces(), 4 + 2);
    double area = 0;
    for (const Tri& t : m.faces) {
        const Vec3 n = (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]);
        EXPECT_GT(n.z(), 0) << "every triangle keeps the polygon's (counter-clockwise) orientation";
        area += 0.5 * n.norm();
    }
    EXPECT_NEAR(area, 3.0 + 1.0, 1e-12);  // the L has area 3, the quad 1
    const MeshTopology t = compute_topology(m);
    EXPECT_TRUE(t.is_disc);
}

}  // namespace
}  // namespace ctmap::test

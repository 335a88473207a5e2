// The path search's graph near a path's own end (cut/approximate_path.h).
//
// A path that leaves its source, goes round and passes by the source again must cross the short
// edges from the source to the paths beside it. Those edges had no Steiner point (the source did
// not count as blocked), so the search found nothing in a region its sector does reach: the cut
// then stopped with "no valid path ... after refinement" (three_peaks, 400 features, twist 8,
// guided by a coarse map). The oracle here is the mesh's own topology: which faces the region
// joins across edges that are not path edges.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <unordered_set>

#include "ctmap/cut/approximate_path.h"
#include "ctmap/cut/work_mesh.h"

namespace ctmap::test {
namespace {

/// A source u at the centre of a small hexagon x0..x5 (radius 0.1) inside a large one y0..y5
/// (radius 1), the ring between them in 12 triangles. Vertex ids: u 0, x_i 1 + i, y_i 7 + i.
TriMesh two_rings() {
    TriMesh m;
    m.positions.push_back(Vec3(0, 0, 0));
    for (double r : {0.1, 1.0})
        for (int i = 0; i < 6; ++i) {
            const double a = i * M_PI / 3;
            m.positions.push_back(Vec3(r * std::cos(a), r * std::sin(a), 0));
        }
    auto x = [](int i) { return 1 + (i % 6); };
    auto y = [](int i) { return 7 + (i % 6); };
    for (int i = 0; i < 6; ++i) m.faces.push_back({0, x(i), x(i + 1)});  // face i: the fan
    for (int i = 0; i < 6; ++i) {
        m.faces.push_back({x(i), y(i), y(i + 1)});
        m.faces.push_back({x(i), y(i + 1), x(i + 1)});
    }
    return m;
}

/// The faces reachable from `start` across edges that are not path edges (the region).
std::vector<char> region(const WorkMesh& m, const std::vector<int>& start, const std::unordered_set<std::uint64_t>& path_edges) {
    std::vector<char> seen(m.faces.size(), 0);
    std::vector<int> stack(start);
    for (int f : start) seen[f] = 1;
    while (!stack.empty()) {
        const int f = stack.back();
        stack.pop_back();
        for (int k = 0; k < 3; ++k) {
            const int e = m.face_edges[f][k];
            if (path_edges.count(m.edges[e])) continue;
            for (int g : m.edge_faces[e])
                if (g >= 0 && !seen[g]) {
                    seen[g] = 1;
                    stack.push_back(g);
                }
        }
    }
    return seen;
}

struct Case {
    TriMesh mesh = two_rings();
    WorkMesh wm{mesh};
    std::vector<char> blocked;
    std::unordered_set<std::uint64_t> path_edges;
    PathConstraints c;
    PathSearchOptions opt;

    /// u (0) to y3 (10). A path runs from u through x0 out to y0 (u's sector starts at it), another
    /// from x1 out to y1, so the ring's cell between them is closed but for the edge x0-x1 back
    /// into u's fan; u may only leave through the fan face (u, x0, x1). Every x_i lies on a path
    /// (blocked), and the edges u-x_i are shorter than the spacing.
    Case() {
        blocked.assign(wm.positions.size(), 0);
        for (int v : {0, 1, 2, 3, 4, 5, 6, 7, 8, 10}) blocked[v] = 1;
        path_edges = {edge_key(0, 1), edge_key(1, 7), edge_key(2, 8)};
        c.source = 0;
        c.target = 10;
        c.blocked = &blocked;
        c.path_edges = &path_edges;
        c.source_sector.faces = {0};
        for (const auto& e : wm.fan(10)) {
            c.target_sector.faces.push_back(e.face);
            c.target_sector.edge_neighbours.push_back(e.from);
            c.target_sector.edge_neighbours.push_back(e.to);
        }
        opt.spacing = 0.5;
        opt.corridor_rings = 0;
    }
    bool region_reaches_target() const {
        const std::vector<char> seen = region(wm, c.source_sector.faces, path_edges);
        return std::any_of(c.target_sector.faces.begin(), c.target_sector.faces.end(), [&](int f) { return seen[f] != 0; });
    }
};

TEST(PathSearch, APathMayPassByItsOwnEnd) {
    Case k;
    ASSERT_TRUE(k.region_reaches_target()) << "the oracle: u's sector and y3 lie in one region";
    const std::optional<FoundPath> p = find_path(k.wm, k.c, k.opt);
    ASSERT_TRUE(p) << "a region that joins the two sectors has a path";
    ASSERT_GE(p->nodes.size(), 3u);
    EXPECT_EQ(p->nodes.front().vertex, 0);
    EXPECT_EQ(p->nodes.back().vertex, 10);
    // It leaves through the only exit of u's face (the edge x0-x1), then passes by u across an
    // edge u-x_i, and never steps on a blocked vertex or along a path edge.
    EXPECT_EQ(std::min(p->nodes[1].a, p->nodes[1].b), 1);
    EXPECT_EQ(std::max(p->nodes[1].a, p->nodes[1].b), 2);
    bool passes_by_u = false;
    for (std::size_t i = 1; i + 1 < p->nodes.size(); ++i) {
        const PathNode& n = p->nodes[i];
        if (n.vertex >= 0) {
            EXPECT_FALSE(k.blocked[n.vertex]) << "node " << i << " is the blocked vertex " << n.vertex;
        } else {
            EXPECT_FALSE(k.path_edges.count(edge_key(n.a, n.b))) << "node " << i << " lies on a path edge";
            EXPECT_GT(n.t, 0.0);
            EXPECT_LT(n.t, 1.0);
            if (std::min(n.a, n.b) == 0) passes_by_u = true;
        }
    }
    EXPECT_TRUE(passes_by_u);
}

TEST(PathSearch, NoPathWhereTheRegionIsClosed) {
    // The control: with u-x1 a path edge too (u's sector closed by paths on both sides), u's face
    // and the ring's cell form a region of their own.
    Case k;
    k.path_edges.insert(edge_key(0, 2));
    ASSERT_FALSE(k.region_reaches_target());
    EXPECT_FALSE(find_path(k.wm, k.c, k.opt));
}

}  // namespace
}  // namespace ctmap::test

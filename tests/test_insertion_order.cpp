// The cut's shortest-first insertion order (cut/insertion_order.h, paper §2.3) against a network
// of our own: which searches it asks for and in which order it inserts. A network whose search
// without refinement finds no path between two features must be asked to refine for that pair,
// told that the plain search already missed (so the cut does not run it again), and every
// interior edge must be inserted exactly once, tree edges before closing edges.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "ctmap/cut/insertion_order.h"

namespace ctmap::test {
namespace {

/// A square of border features 0..3 around two interior features 4 and 5: border edges 01, 12,
/// 23, 30; interior edges 04, 14, 45, 25, 35, 24 (the diagonal 4-2 splits the right half).
FeatureTriangulation square_with_two_inside() {
    FeatureTriangulation ft;
    ft.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}, {0.3, 0.5}, {0.7, 0.5}};
    ft.border = {0, 1, 2, 3};
    const std::vector<std::array<int, 2>> border = {{0, 1}, {1, 2}, {2, 3}, {0, 3}};
    const std::vector<std::array<int, 2>> inside = {{0, 4}, {1, 4}, {4, 5}, {2, 5}, {3, 5}, {3, 4}, {2, 4}};
    for (const auto& e : border) ft.edges.push_back(e), ft.edge_on_border.push_back(true);
    for (const auto& e : inside) ft.edges.push_back(e), ft.edge_on_border.push_back(false);
    return ft;
}

double distance(const FeatureTriangulation& ft, int u, int w) { return (ft.points[u] - ft.points[w]).norm(); }

struct Call {
    int u, w;
    bool refine, missed;
    int version;  // insertions before the call
};

TEST(InsertionOrder, APairWhosePlainSearchMissedIsRefinedWithoutSearchingAgain) {
    const FeatureTriangulation ft = square_with_two_inside();
    // The network: no path from or to feature 4 without refinement (a feature in a narrow spot);
    // a refined search finds one. Paths' lengths are the features' distances.
    std::vector<Call> calls;
    std::vector<std::array<int, 2>> inserted;
    auto blocked = [](int u, int w) { return u == 4 || w == 4; };
    PathNetworkAccess net;
    net.find = [&](int u, int w, bool refine, bool missed) -> std::optional<FoundPath> {
        calls.push_back({u, w, refine, missed, int(inserted.size())});
        if (blocked(u, w) && !refine) return std::nullopt;
        FoundPath p;
        p.length = distance(ft, u, w);
        return p;
    };
    net.insert = [&](int u, int w, const FoundPath&) {
        inserted.push_back({std::min(u, w), std::max(u, w)});
        return true;
    };
    net.lower_bound = [&](int u, int w) { return distance(ft, u, w); };
    ASSERT_TRUE(insert_shortest_path_first(ft, net));

    // Every interior edge once.
    std::set<std::array<int, 2>> once(inserted.begin(), inserted.end());
    EXPECT_EQ(once.size(), inserted.size());
    EXPECT_EQ(inserted.size(), 7u);
    // The tree (features 4 and 5 joined to the border) before any closing edge: the first two
    // insertions reach both interior features.
    ASSERT_GE(inserted.size(), 2u);
    std::set<int> first_two;
    for (int k = 0; k < 2; ++k) first_two.insert(inserted[k][0]), first_two.insert(inserted[k][1]);
    EXPECT_TRUE(first_two.count(4) && first_two.count(5));
    // Whenever the order asks for a refined search, a plain search of the same pair missed in the
    // same network, and the call says so; no pair's plain search runs twice in one network.
    std::map<std::array<int, 3>, int> plain;  // (u, w, insertions before) -> plain searches
    int refined = 0;
    for (const Call& c : calls) {
        const std::array<int, 3> key = {c.u, c.w, c.version};
        if (!c.refine) {
            ++plain[key];
            continue;
        }
        ++refined;
        EXPECT_TRUE(blocked(c.u, c.w) && plain.count(key)) << "refined search of " << c.u << "-" << c.w;
        EXPECT_TRUE(c.missed) << "refined search of " << c.u << "-" << c.w << " not told the plain one missed";
    }
    // Each of feature 4's five edges needed the refinement.
    EXPECT_EQ(refined, 5);
    for (const auto& [key, n] : plain)
        EXPECT_EQ(n, 1) << key[0] << "-" << key[1] << " searched twice at version " << key[2];
}

}  // namespace
}  // namespace ctmap::test

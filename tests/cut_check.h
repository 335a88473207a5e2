#pragma once
// Independent checks of a CutMesh (issue 3, must-show 1): everything a later stage relies on.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "ctmap/certify/certificate.h"
#include "ctmap/cut/cut_mesh.h"
#include "ctmap/map_texture.h"

namespace ctmap::test {

inline double mesh_area(const TriMesh& m) {
    double a = 0;
    for (const Tri& t : m.faces)
        a += 0.5 * (m.positions[t[1]] - m.positions[t[0]]).cross(m.positions[t[2]] - m.positions[t[0]]).norm();
    return a;
}

/// Asserts the cut's invariants; `what` names the case in failure messages.
inline void expect_valid_cut(const TriMesh& input, const FeatureTriangulation& ft, const CutMesh& cut,
                             const std::string& what) {
    SCOPED_TRACE(what);
    const TriMesh& m = cut.mesh;
    // Input vertices kept, in order, at the same positions.
    ASSERT_GE(m.num_vertices(), input.num_vertices());
    for (int v = 0; v < input.num_vertices(); ++v) ASSERT_EQ(m.positions[v], input.positions[v]);
    // The surface is unchanged: same area, inserted vertices on the input faces.
    const double a0 = mesh_area(input), a1 = mesh_area(m);
    EXPECT_NEAR(a1 / a0, 1.0, 1e-9);
    Eigen::AlignedBox3d box;
    for (const Vec3& p : input.positions) box.extend(p);
    const double diag = box.diagonal().norm();
    for (int v = input.num_vertices(); v < m.num_vertices(); ++v) {
        const int f = cut.vertex_face[v];
        ASSERT_GE(f, 0);
        const Vec3& l = cut.vertex_bary[v];
        EXPECT_GE(l.minCoeff(), -1e-9) << "vertex " << v;
        const Tri& t = input.faces[f];
        const Vec3 p = l[0] * input.positions[t[0]] + l[1] * input.positions[t[1]] + l[2] * input.positions[t[2]];
        EXPECT_LE((p - m.positions[v]).norm(), 1e-9 * diag) << "vertex " << v << " is off the input surface";
    }
    // One patch per image triangle, each a disc bounded by exactly its three sides.
    ASSERT_EQ(cut.patches.size(), ft.triangles.size());
    ASSERT_EQ(cut.face_patch.size(), m.faces.size());
    std::vector<std::vector<int>> faces_of(cut.patches.size());
    for (int f = 0; f < m.num_faces(); ++f) {
        ASSERT_GE(cut.face_patch[f], 0);
        faces_of[cut.face_patch[f]].push_back(f);
    }
    for (std::size_t p = 0; p < cut.patches.size(); ++p) {
        const Patch& patch = cut.patches[p];
        ASSERT_FALSE(faces_of[p].empty()) << "patch " << p << " is empty";
        std::map<std::pair<int, int>, int> directed;
        std::set<int> verts;
        for (int f : faces_of[p])
            for (int k = 0; k < 3; ++k) {
                directed[{m.faces[f][k], m.faces[f][(k + 1) % 3]}]++;
                verts.insert(m.faces[f][k]);
            }
        std::set<std::pair<int, int>> border, undirected;
        for (const auto& [e, n] : directed) {
            undirected.insert({std::min(e.first, e.second), std::max(e.first, e.second)});
            if (!directed.count({e.second, e.first})) border.insert(e);
        }
        const int euler = int(verts.size()) - int(undirected.size()) + int(faces_of[p].size());
        EXPECT_EQ(euler, 1) << "patch " << p << " is not a disc";
        std::set<std::pair<int, int>> sides;
        for (int k = 0; k < 3; ++k) {
            const auto& s = patch.sides[k];
            EXPECT_EQ(s.front(), cut.feature_vertex[patch.corners[k]]);
            EXPECT_EQ(s.back(), cut.feature_vertex[patch.corners[(k + 1) % 3]]);
            for (std::size_t i = 0; i + 1 < s.size(); ++i) sides.insert({s[i], s[i + 1]});
        }
        EXPECT_EQ(border, sides) << "patch " << p << " is not bounded by exactly its three paths (patch on the left)";
    }
    // Paths share nothing but their end features; no feature inside a path.
    std::map<int, int> owner;
    std::set<int> features(cut.feature_vertex.begin(), cut.feature_vertex.end());
    for (std::size_t e = 0; e < ft.edges.size(); ++e) {
        const int a = ft.edges[e][0], b = ft.edges[e][1];
        const Patch* holder = nullptr;
        int side = -1;
        for (const Patch& p : cut.patches)
            for (int k = 0; k < 3; ++k)
                if ((p.corners[k] == a && p.corners[(k + 1) % 3] == b) || (p.corners[k] == b && p.corners[(k + 1) % 3] == a)) {
                    holder = &p;
                    side = k;
                }
        ASSERT_NE(holder, nullptr) << "edge " << a << "-" << b << " has no patch";
        const auto& s = holder->sides[side];
        for (std::size_t i = 1; i + 1 < s.size(); ++i) {
            EXPECT_FALSE(features.count(s[i])) << "path " << a << "-" << b << " runs through a feature";
            auto [it, fresh] = owner.emplace(s[i], int(e));
            EXPECT_TRUE(fresh) << "paths " << it->second << " and " << e << " share vertex " << s[i];
        }
    }
    // Each feature lies in exactly the patches of its image triangles.
    for (int i = 0; i < int(cut.feature_vertex.size()); ++i) {
        std::set<int> want, got;
        for (int t = 0; t < int(ft.triangles.size()); ++t)
            for (int k = 0; k < 3; ++k)
                if (ft.triangles[t][k] == i) want.insert(t);
        for (int f = 0; f < m.num_faces(); ++f)
            for (int k = 0; k < 3; ++k)
                if (m.faces[f][k] == cut.feature_vertex[i]) got.insert(cut.face_patch[f]);
        EXPECT_EQ(want, got) << "feature " << i;
    }
}

/// The map of `features` stopping after the paper's relaxation (`opt.refine_mode` is set to
/// paper), with the cut checked and the map certified (0 flipped, features exact).
inline MapResult certified_paper_map(const TriMesh& mesh, const std::vector<MapFeature>& features, MapOptions opt,
                                     const std::string& what) {
    opt.refine_mode = RefineMode::paper;
    MapResult r = map_texture(mesh, features, opt);
    expect_valid_cut(mesh, r.triangulation, r.cut, what);
    const Certificate cert = certify(r.textured(), r.cut.feature_vertex, r.feature_uv, {false});
    EXPECT_TRUE(cert.valid) << what;
    EXPECT_EQ(cert.flipped, 0) << what;
    EXPECT_EQ(cert.feature_max_error, 0.0) << what;
    return r;
}

}  // namespace ctmap::test

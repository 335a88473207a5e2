// Issue 16: a caller's mistake reaches map_texture's caller as BadInput (or TopologyError, a
// BadInput) naming what is wrong, never as InternalError from deep in the pipeline. One test per
// precondition, on the shipped example's mesh and features.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <limits>

#include "ctmap/errors.h"
#include "ctmap/io/features.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

struct Example {
    TriMesh mesh = read_mesh(data("meshes/nefertiti.off"));
    std::vector<MapFeature> features;
    Example() {
        FeatureSet fs = read_features(data("features/nefertiti_astronaut.json"));
        int w = 0, h = 0;
        resolve_feature_image(fs, "", w, h);
        features = map_features(fs, w, h);
    }
    /// The index of the i-th feature that is not on the mesh border (the example's rim* are).
    int interior(int i) const {
        for (int k = 0; k < int(features.size()); ++k)
            if (features[k].name.rfind("rim", 0) != 0 && i-- == 0) return k;
        return -1;
    }
};

/// map_texture throws BadInput (not InternalError) whose message holds every word of `words` and
/// names no file (a library caller gave none; issue 16), and `naming_file` adds a caller's file
/// to it, keeping the exception's type.
void expect_bad_input(const TriMesh& mesh, const std::vector<MapFeature>& features, std::vector<std::string> words) {
    try {
        map_texture(mesh, features);
        ADD_FAILURE() << "no exception";
    } catch (const BadInput& e) {
        for (const std::string& w : words) EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
        EXPECT_EQ(e.file(), "") << e.what();
        EXPECT_EQ(std::string(e.what()), e.problem());
        const bool topology = dynamic_cast<const TopologyError*>(&e) != nullptr;
        try {
            naming_file("in.json", [&] { return map_texture(mesh, features); });
            ADD_FAILURE() << "no exception the second time";
        } catch (const TopologyError& t) {
            EXPECT_TRUE(topology) << t.what();
            EXPECT_EQ(std::string(t.what()), e.what()) << "a mesh problem is not the features file's";
        } catch (const BadInput& b) {
            EXPECT_FALSE(topology) << b.what();
            EXPECT_EQ(std::string(b.what()), "in.json: " + std::string(e.what()));
        }
    } catch (const std::exception& e) {
        ADD_FAILURE() << "not BadInput: " << e.what();
    }
}

TEST(LibraryPreconditions, TwoFeaturesAtOneImagePoint) {
    Example x;
    const int a = x.interior(0), b = x.interior(1);
    x.features[b].uv = x.features[a].uv;
    expect_bad_input(x.mesh, x.features, {x.features[a].name, x.features[b].name, "same image point"});
}

TEST(LibraryPreconditions, NonFiniteUv) {
    Example x;
    const int a = x.interior(0);
    x.features[a].uv.x() = std::numeric_limits<double>::quiet_NaN();
    expect_bad_input(x.mesh, x.features, {x.features[a].name, "not finite"});
}

TEST(LibraryPreconditions, VertexOutOfRange) {
    Example x;
    const int a = x.interior(0);
    x.features[a].vertex = x.mesh.num_vertices() + 7;
    expect_bad_input(x.mesh, x.features, {x.features[a].name, "does not exist"});
}

TEST(LibraryPreconditions, TwoFeaturesAtOneVertex) {
    Example x;
    const int a = x.interior(0), b = x.interior(1);
    x.features[b].vertex = x.features[a].vertex;
    x.features[b].point = x.features[a].point;
    expect_bad_input(x.mesh, x.features, {x.features[a].name, x.features[b].name, "same mesh vertex"});
}

TEST(LibraryPreconditions, NonManifoldEdge) {
    Example x;
    // An interior edge (both of its faces in the mesh), then a third face on it.
    std::set<std::pair<int, int>> directed;
    for (const Tri& t : x.mesh.faces)
        for (int k = 0; k < 3; ++k) directed.emplace(t[k], t[(k + 1) % 3]);
    const Tri t = *std::find_if(x.mesh.faces.begin(), x.mesh.faces.end(),
                                [&](const Tri& f) { return directed.count({f[1], f[0]}) > 0; });
    x.mesh.positions.push_back(Vec3(9, 9, 9));
    x.mesh.faces.push_back({t[1], t[0], x.mesh.num_vertices() - 1});
    expect_bad_input(x.mesh, x.features, {"non-manifold edge"});
}

TEST(LibraryPreconditions, ClosedMesh) {
    TriMesh tet;
    tet.positions = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1)};
    tet.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
    std::vector<MapFeature> f(3);
    for (int i = 0; i < 3; ++i) {
        f[i].name = "f" + std::to_string(i);
        f[i].vertex = i;
        f[i].uv = Vec2(0.2 + 0.3 * i, 0.3 + 0.2 * (i % 2));
    }
    expect_bad_input(tet, f, {"closed"});
}

// The matrix overload gives the map of the TriMesh overload, corner by corner, and checks its arrays.
TEST(LibraryArrays, EigenOverloadGivesTheSameMap) {
    Example x;
    Eigen::MatrixXd V(x.mesh.num_vertices(), 3);
    Eigen::MatrixXi F(x.mesh.num_faces(), 3);
    for (int i = 0; i < x.mesh.num_vertices(); ++i) V.row(i) = x.mesh.positions[i].transpose();
    for (int f = 0; f < x.mesh.num_faces(); ++f) F.row(f) << x.mesh.faces[f][0], x.mesh.faces[f][1], x.mesh.faces[f][2];
    const MapArrays a = map_texture(V, F, x.features);
    const MapResult r = map_texture(x.mesh, x.features);
    ASSERT_TRUE(a.result.certificate.valid);
    ASSERT_EQ(a.F.rows(), r.cut.mesh.num_faces());
    for (int f = 0; f < r.cut.mesh.num_faces(); ++f)
        for (int k = 0; k < 3; ++k) {
            ASSERT_EQ(a.F(f, k), r.cut.mesh.faces[f][k]);
            ASSERT_EQ(a.UV(3 * f + k, 0), r.uv[r.cut.mesh.faces[f][k]].x());
            ASSERT_EQ(a.UV(3 * f + k, 1), r.uv[r.cut.mesh.faces[f][k]].y());
        }
    ASSERT_EQ(a.feature_vertex.size(), Eigen::Index(r.cut.feature_vertex.size()));
    for (std::size_t i = 0; i < r.cut.feature_vertex.size(); ++i) EXPECT_EQ(a.feature_vertex(Eigen::Index(i)), r.cut.feature_vertex[i]);
    EXPECT_EQ(a.chart.size(), a.F.rows());
    Eigen::MatrixXi bad = F;
    bad(4, 2) = int(V.rows());
    EXPECT_THROW(map_texture(V, bad, x.features), BadInput);
    EXPECT_THROW(map_texture(Eigen::MatrixXd(V.leftCols(2)), F, x.features), BadInput);
}

}  // namespace
}  // namespace ctmap::test

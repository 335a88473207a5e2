// The cut (issue 3): triangulation in the image and matching patches on real meshes.
#include "ctmap/cut/cut_mesh.h"
#include "ctmap/domain/feature_triangulation.h"
#include "ctmap/errors.h"
#include "ctmap/io/features.h"
#include "ctmap/io/read_mesh.h"
#include "cut_check.h"
#include "test_support.h"

namespace ctmap::test {
namespace {

std::vector<Vec2> to_uv(const FeatureSet& fs, int w, int h) {
    std::vector<Vec2> uv;
    for (const Feature& f : fs.features) uv.emplace_back(f.image.x() / w, 1.0 - f.image.y() / h);
    return uv;
}

TEST(Cut, NefertitiExample) {
    const TriMesh mesh = read_mesh(data("meshes/nefertiti.off"));
    const FeatureSet fs = read_features(data("features/nefertiti_astronaut.json"));
    std::vector<int> fv;
    std::vector<std::string> names;
    for (const Feature& f : fs.features) {
        fv.push_back(f.vertex);
        names.push_back(f.name);
    }
    const auto border = border_features(mesh, fv);
    EXPECT_EQ(border.size(), 8u);
    const FeatureTriangulation ft = triangulate_features(to_uv(fs, 512, 512), border, names);
    EXPECT_FALSE(ft.mirrored);
    CutStats stats;
    const CutMesh cut = cut_mesh(mesh, fv, ft, {}, &stats);
    expect_valid_cut(mesh, ft, cut, "nefertiti");
    std::cout << "nefertiti: " << ft.triangles.size() << " patches, " << stats.paths << " paths, "
              << stats.inserted_vertices << " inserted vertices, fallback " << stats.fallback_fired << "\n";
}

}  // namespace
}  // namespace ctmap::test

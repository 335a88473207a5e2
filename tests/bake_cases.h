// The UV layouts the bake tests give ONTO (tests/test_bake*.cpp): a user's own layout of a mesh,
// made independently of the map being baked.
#pragma once
#include <cmath>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap::test {

/// A planar layout, the front view: x and y of every vertex into [0.05, 0.95] (one to one on a
/// relief such as nefertiti, whose faces all face +z). With `texels` > 0 each UV is moved onto the
/// nearest texel centre of a `texels` x `texels` texture (u = (i + 0.5) / texels, v = 1 - (j + 0.5) / texels).
inline std::vector<Vec2> planar_uvs(const TriMesh& mesh, int texels = 0) {
    Vec3 lo = mesh.positions[0], hi = lo;
    for (const Vec3& p : mesh.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    std::vector<Vec2> uv;
    for (const Vec3& p : mesh.positions) {
        Vec2 t(0.05 + 0.9 * (p.x() - lo.x()) / (hi.x() - lo.x()), 0.05 + 0.9 * (p.y() - lo.y()) / (hi.y() - lo.y()));
        if (texels > 0) {
            const double i = std::round(t.x() * texels - 0.5), j = std::round((1 - t.y()) * texels - 0.5);
            t = Vec2((i + 0.5) / texels, 1 - (j + 0.5) / texels);
        }
        uv.push_back(t);
    }
    return uv;
}

}  // namespace ctmap::test

#include "ctmap/io/vertex_normals.h"

#include <cmath>

namespace ctmap {

std::vector<Vec3> vertex_normals(const TriMesh& mesh) {
    std::vector<Vec3> n(mesh.positions.size(), Vec3::Zero());
    if (mesh.positions.empty()) return n;
    Vec3 lo = mesh.positions[0], hi = lo;
    for (const Vec3& p : mesh.positions) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
    const Vec3 center = 0.5 * lo + 0.5 * hi;
    double half = (0.5 * hi - 0.5 * lo).maxCoeff();
    if (!(half > 0) || !std::isfinite(half)) half = 1;
    auto unit = [&](int v) { return Vec3((mesh.positions[v] - center) / half); };
    for (const Tri& t : mesh.faces) {
        const Vec3 a = unit(t[0]);
        const Vec3 c = (unit(t[1]) - a).cross(unit(t[2]) - a);
        for (int k = 0; k < 3; ++k) n[t[k]] += c;
    }
    for (Vec3& v : n) {
        const double len = v.norm();
        v = len > 0 && std::isfinite(len) ? Vec3(v / len) : Vec3(0, 0, 1);
    }
    return n;
}

}  // namespace ctmap

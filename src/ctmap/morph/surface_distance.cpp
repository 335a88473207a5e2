#include "ctmap/morph/surface_distance.h"

#include <algorithm>
#include <cmath>
#include <set>

namespace ctmap {

double hausdorff_from(const TriMesh& from, const TriMesh& to, int samples_per_face) {
    const SurfaceDistance d(to);
    double h = 0;
    for (const Vec3& p : from.positions) h = std::max(h, d.distance(p));
    // Fixed interior points per face (barycentric), besides the centroid and edge midpoints.
    static const double pattern[][3] = {{0.6, 0.2, 0.2}, {0.2, 0.6, 0.2}, {0.2, 0.2, 0.6}, {0.45, 0.45, 0.1},
                                        {0.1, 0.45, 0.45}, {0.45, 0.1, 0.45}};
    for (const Tri& t : from.faces) {
        const Vec3 &a = from.positions[t[0]], &b = from.positions[t[1]], &c = from.positions[t[2]];
        h = std::max({h, d.distance((a + b + c) / 3), d.distance(0.5 * (a + b)), d.distance(0.5 * (b + c)),
                      d.distance(0.5 * (c + a))});
        for (int k = 0; k < std::min(samples_per_face, 6); ++k)
            h = std::max(h, d.distance(pattern[k][0] * a + pattern[k][1] * b + pattern[k][2] * c));
    }
    return h;
}

double mean_edge_length(const TriMesh& mesh) {
    std::set<std::pair<int, int>> seen;
    double sum = 0;
    for (const Tri& t : mesh.faces)
        for (int k = 0; k < 3; ++k) {
            const int u = t[k], v = t[(k + 1) % 3];
            if (seen.emplace(std::min(u, v), std::max(u, v)).second) sum += (mesh.positions[u] - mesh.positions[v]).norm();
        }
    return seen.empty() ? 0 : sum / double(seen.size());
}

}  // namespace ctmap

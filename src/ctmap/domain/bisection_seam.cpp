#include "ctmap/domain/bisection_seam.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "ctmap/errors.h"

namespace ctmap {

std::vector<int> bisection_seam_vertices(const TriMesh& mesh, int count) {
    if (count < 3) throw BadInput("", "a seam needs at least 3 features, asked for " + std::to_string(count));
    Eigen::AlignedBox3d box;
    for (const Vec3& p : mesh.positions) box.extend(p);
    const Vec3 size = box.sizes(), centre = box.center();
    int axis = 0;
    for (int k = 1; k < 3; ++k)
        if (size[k] < size[axis]) axis = k;
    const int u = (axis + 1) % 3, w = (axis + 2) % 3;
    // Vertices within a slab round the plane; the slab widens until every direction finds one.
    std::vector<int> out;
    for (double slab = 0.01; slab <= 0.5 && int(out.size()) < count; slab *= 2) {
        out.assign(count, -1);
        std::vector<double> best(count, -std::numeric_limits<double>::infinity());
        const double half_width = slab * size.norm();
        for (int v = 0; v < mesh.num_vertices(); ++v) {
            const Vec3 d = mesh.positions[v] - centre;
            if (std::abs(d[axis]) > half_width) continue;
            const double angle = std::atan2(d[w], d[u]);
            // The nearest direction of the `count` equal angles; farthest vertex wins it.
            const int k = int(std::lround((angle + M_PI) / (2 * M_PI) * count)) % count;
            const double dir = -M_PI + 2 * M_PI * k / count;
            const double reach = d[u] * std::cos(dir) + d[w] * std::sin(dir);
            if (reach > best[k]) best[k] = reach, out[k] = v;
        }
        // Each vertex once (one may win several directions), in the angular order.
        std::vector<int> kept;
        for (int v : out)
            if (v >= 0 && std::find(kept.begin(), kept.end(), v) == kept.end()) kept.push_back(v);
        out = std::move(kept);
    }
    if (out.size() < 3) throw BadInput("", "no seam round the mesh's middle: fewer than 3 vertices near its plane");
    return out;
}

}  // namespace ctmap

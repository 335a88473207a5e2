#include "ctmap/subdivide.h"

#include <unordered_map>

#include "ctmap/cut/work_mesh.h"

namespace ctmap {

TriMesh subdivide_midpoint(const TriMesh& mesh, int levels) {
    TriMesh m = mesh;
    for (int level = 0; level < levels; ++level) {
        TriMesh next;
        next.positions = m.positions;
        next.positions.reserve(m.positions.size() + m.faces.size() * 3 / 2 + 16);
        next.faces.reserve(m.faces.size() * 4);
        std::unordered_map<std::uint64_t, int> midpoint;
        midpoint.reserve(m.faces.size() * 2);
        auto mid = [&](int a, int b) {
            auto [it, fresh] = midpoint.emplace(edge_key(a, b), int(next.positions.size()));
            if (fresh) next.positions.push_back(0.5 * (m.positions[a] + m.positions[b]));
            return it->second;
        };
        for (const Tri& t : m.faces) {
            const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
            next.faces.push_back({t[0], ab, ca});
            next.faces.push_back({ab, t[1], bc});
            next.faces.push_back({ca, bc, t[2]});
            next.faces.push_back({ab, bc, ca});
        }
        m = std::move(next);
    }
    return m;
}

}  // namespace ctmap

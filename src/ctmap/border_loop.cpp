#include "ctmap/border_loop.h"

#include <algorithm>

namespace ctmap {

std::vector<int> border_loop(const TriMesh& mesh) { return border_loop(mesh.faces, mesh.num_vertices()); }

std::vector<int> border_loop(const std::vector<Tri>& faces, int num_vertices) {
    const int nv = num_vertices, nf = int(faces.size());
    // Faces around each vertex (counting sort), then: the directed edge (a, b) of a face is on
    // the border when no face around b has the edge (b, a).
    std::vector<int> first(nv + 1, 0), around(std::size_t(3) * nf);
    for (const Tri& t : faces)
        for (int v : t) ++first[v + 1];
    for (int v = 0; v < nv; ++v) first[v + 1] += first[v];
    std::vector<int> fill(first.begin(), first.end() - 1);
    for (int f = 0; f < nf; ++f)
        for (int v : faces[f]) around[fill[v]++] = f;
    std::vector<int> next(nv, -1);
    int border = 0;
    for (const Tri& t : faces)
        for (int k = 0; k < 3; ++k) {
            const int a = t[k], b = t[(k + 1) % 3];
            const bool twin = std::any_of(around.begin() + first[b], around.begin() + first[b + 1], [&](int g) {
                const Tri& s = faces[g];
                for (int j = 0; j < 3; ++j)
                    if (s[j] == b && s[(j + 1) % 3] == a) return true;
                return false;
            });
            if (!twin) next[a] = b, ++border;
        }
    std::vector<int> loop;
    const auto start = std::find_if(next.begin(), next.end(), [](int n) { return n >= 0; });
    if (start == next.end()) return loop;
    const int s = int(start - next.begin());
    int v = s;
    do {
        loop.push_back(v);
        v = next[v];
    } while (v != s && v >= 0 && int(loop.size()) <= border);
    return loop;
}

}  // namespace ctmap

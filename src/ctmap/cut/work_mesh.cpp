#include "ctmap/cut/work_mesh.h"

#include <algorithm>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include "ctmap/border_loop.h"
#include "ctmap/errors.h"

namespace ctmap {

WorkMesh::WorkMesh(const TriMesh& m)
    : positions(m.positions), faces(m.faces), origin(m.faces.size()), site(m.positions.size()), input_faces(m.faces) {
    std::iota(origin.begin(), origin.end(), 0);
    for (int v = 0; v < int(site.size()); ++v) site[v] = {v, v};
    rebuild();
}

void WorkMesh::rebuild() {
    edges.clear();
    edge_faces.clear();
    vertex_faces.assign(positions.size(), {});
    face_edges.assign(faces.size(), {-1, -1, -1});
    for (int f = 0; f < int(faces.size()); ++f)
        for (int k = 0; k < 3; ++k) vertex_faces[faces[f][k]].push_back(f);
    // Edge ids in order of first appearance (face order, then corner order); the twin of a
    // face's edge (a, b) is the face around b with the edge (b, a).
    for (int f = 0; f < int(faces.size()); ++f)
        for (int k = 0; k < 3; ++k) {
            if (face_edges[f][k] >= 0) continue;
            const int a = faces[f][k], b = faces[f][(k + 1) % 3];
            const int e = int(edges.size());
            edges.push_back(edge_key(a, b));
            edge_faces.push_back({f, -1});
            face_edges[f][k] = e;
            for (int g : vertex_faces[b]) {
                if (g == f) continue;
                const int j = corner_of(g, b);
                if (faces[g][(j + 1) % 3] != a) continue;
                if (face_edges[g][j] >= 0)
                    throw InternalError("the mesh is not manifold at edge " + std::to_string(a) + "-" + std::to_string(b));
                face_edges[g][j] = e;
                edge_faces[e][1] = g;
            }
        }
}

void WorkMesh::replace_faces(const std::vector<int>& removed, const std::vector<Tri>& added,
                             const std::vector<int>& added_origin) {
    std::vector<int> touched_edges;
    for (int f : removed) {
        const Tri& t = faces[f];
        for (int k = 0; k < 3; ++k) {
            const int e = face_edges[f][k];
            auto& ef = edge_faces[e];
            if (ef[0] == f) ef = {ef[1], -1};
            else if (ef[1] == f) ef[1] = -1;
            touched_edges.push_back(e);
            auto& vf = vertex_faces[t[k]];
            vf.erase(std::find(vf.begin(), vf.end(), f));
        }
    }
    vertex_faces.resize(positions.size());
    // The removed faces' edges by key (a scan of them per added edge was quadratic in the faces
    // replaced: straighten_path replaces a whole input face's refinement at once).
    std::unordered_map<std::uint64_t, int> touched;
    for (int x : touched_edges) touched.emplace(edges[x], x);
    for (std::size_t i = 0; i < added.size(); ++i) {
        int id;
        if (i < removed.size()) {
            id = removed[i];
            faces[id] = added[i];
            origin[id] = added_origin[i];
        } else {
            id = int(faces.size());
            faces.push_back(added[i]);
            origin.push_back(added_origin[i]);
            face_edges.push_back({-1, -1, -1});
        }
        const Tri& t = added[i];
        for (int k = 0; k < 3; ++k) {
            const int a = t[k], b = t[(k + 1) % 3];
            // The edge as it already is: on a live face, or (both its faces replaced) among the
            // removed faces' edges, which keeps its id.
            int e = find_edge(a, b);
            if (e < 0) {
                const auto it = touched.find(edge_key(a, b));
                if (it != touched.end()) e = it->second;
            }
            if (e < 0) {
                e = int(edges.size());
                edges.push_back(edge_key(a, b));
                edge_faces.push_back({-1, -1});
            }
            face_edges[id][k] = e;
            auto& ef = edge_faces[e];
            if (ef[0] < 0) ef[0] = id;
            else if (ef[1] < 0) ef[1] = id;
            else throw InternalError("the refined mesh would not be manifold at edge " + std::to_string(a) + "-" + std::to_string(b));
        }
        for (int k = 0; k < 3; ++k) vertex_faces[t[k]].push_back(id);
    }
    // Fewer faces than removed (straighten_path removes vertices): the last faces fill the holes,
    // so face ids stay 0 .. size - 1.
    std::vector<int> holes(removed.begin() + std::min(removed.size(), added.size()), removed.end());
    std::sort(holes.rbegin(), holes.rend());
    for (int h : holes) {
        const int last = int(faces.size()) - 1;
        if (h != last) {
            faces[h] = faces[last];
            origin[h] = origin[last];
            face_edges[h] = face_edges[last];
            for (int k = 0; k < 3; ++k) {
                std::replace(vertex_faces[faces[h][k]].begin(), vertex_faces[faces[h][k]].end(), last, h);
                auto& ef = edge_faces[face_edges[h][k]];
                std::replace(ef.begin(), ef.end(), last, h);
            }
        }
        faces.pop_back();
        origin.pop_back();
        face_edges.pop_back();
    }
}

std::vector<WorkMesh::FanEntry> WorkMesh::fan(int v) const {
    // Per incident face, the corners after v in its orientation.
    std::vector<FanEntry> entries;
    for (int f : vertex_faces[v]) {
        const Tri& t = faces[f];
        const int k = t[0] == v ? 0 : t[1] == v ? 1 : 2;
        entries.push_back({f, t[(k + 1) % 3], t[(k + 2) % 3]});
    }
    // Start at the face whose `from` edge is on the border (no face ends at it), else anywhere.
    // Linear in the degree (hash maps): straightened paths give some vertices thousands of faces.
    std::unordered_map<int, int> starting_at;  // `from` vertex -> entry
    std::unordered_set<int> ends;
    for (int i = 0; i < int(entries.size()); ++i) starting_at[entries[i].from] = i, ends.insert(entries[i].to);
    int start = 0;
    for (int i = 0; i < int(entries.size()); ++i)
        if (!ends.count(entries[i].from)) {
            start = i;
            break;
        }
    std::vector<FanEntry> out{entries[start]};
    while (out.size() < entries.size()) {
        const auto it = starting_at.find(out.back().to);
        if (it == starting_at.end() || it->second == start)
            throw InternalError("the mesh is not manifold around vertex " + std::to_string(v));
        out.push_back(entries[it->second]);
    }
    return out;
}

std::vector<int> WorkMesh::border_loop() const { return ctmap::border_loop(faces, num_vertices()); }

}  // namespace ctmap

#include "ctmap/cut/insert_path.h"

#include "ctmap/cut/face_frame.h"
#include "ctmap/errors.h"

namespace ctmap {
namespace {

using face_frame::CDT;
using face_frame::K;

/// What to add to one face: points on its edges, points inside, and chords between vertices.
struct FaceEdit {
    struct EdgePoint {
        int vertex, a, b;
        double t;  // position a + t (b - a)
    };
    std::vector<EdgePoint> edge_points;
    std::vector<std::pair<int, Vec3>> inner_points;  // vertex, barycentric
    std::vector<std::pair<int, int>> chords;
};

/// The point in the face's affine frame (face_frame.h).
K::Point_2 frame_point(const Tri& t, const FaceEdit::EdgePoint& p) {
    for (int k = 0; k < 3; ++k) {
        const int u = t[k], w = t[(k + 1) % 3];
        if ((p.a == u && p.b == w) || (p.a == w && p.b == u)) {
            const double s = p.a == u ? p.t : 1.0 - p.t;  // parameter from corner k
            return face_frame::side_point(k, s);
        }
    }
    throw InternalError("insert_path: a point is not on the face it was assigned to");
}

void apply_edits(WorkMesh& mesh, std::map<int, FaceEdit>& edits) {
    std::vector<int> removed;
    std::vector<Tri> added;
    std::vector<int> added_origin;
    for (auto& [f, edit] : edits) {
        const Tri t = mesh.faces[f];
        CDT cdt;
        std::vector<std::pair<K::Point_2, int>> pts = {{{0, 0}, t[0]}, {{1, 0}, t[1]}, {{1, 1}, t[2]}};
        for (const auto& p : edit.edge_points) pts.push_back({frame_point(t, p), p.vertex});
        for (const auto& [v, l] : edit.inner_points) pts.push_back({{l[1] + l[2], l[2]}, v});
        std::map<int, CDT::Vertex_handle> handle;
        for (const auto& [p, v] : pts) {
            if (handle.count(v)) continue;
            CDT::Vertex_handle h = cdt.insert(p);
            h->info() = v;
            handle[v] = h;
        }
        if (cdt.number_of_vertices() != handle.size())
            throw InternalError("insert_path: two inserted points coincide in face " + std::to_string(f));
        for (const auto& [a, b] : edit.chords)
            if (a != b) cdt.insert_constraint(handle.at(a), handle.at(b));
        if (cdt.number_of_vertices() != handle.size())
            throw InternalError("insert_path: the path crosses itself in face " + std::to_string(f));
        for (auto fit = cdt.finite_faces_begin(); fit != cdt.finite_faces_end(); ++fit) {
            added.push_back({fit->vertex(0)->info(), fit->vertex(1)->info(), fit->vertex(2)->info()});
            added_origin.push_back(mesh.origin[f]);
        }
        removed.push_back(f);
    }
    mesh.replace_faces(removed, added, added_origin);
}

}  // namespace

std::vector<int> insert_path(WorkMesh& mesh, const std::vector<PathNode>& nodes) {
    std::map<int, FaceEdit> edits;
    std::vector<int> chain;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const PathNode& n = nodes[i];
        int v = n.vertex;
        if (v < 0) {
            v = mesh.num_vertices();
            mesh.positions.push_back(mesh.positions[n.a] + n.t * (mesh.positions[n.b] - mesh.positions[n.a]));
            mesh.site.push_back(mesh.edge_site(n.a, n.b));
            const int e = mesh.find_edge(n.a, n.b);
            for (int f : mesh.edge_faces.at(e))
                if (f >= 0) edits[f].edge_points.push_back({v, n.a, n.b, n.t});
        }
        if (i > 0 && n.face >= 0) edits[n.face].chords.emplace_back(chain.back(), v);
        chain.push_back(v);
    }
    apply_edits(mesh, edits);
    return chain;
}

int insert_point(WorkMesh& mesh, int f, const Vec3& l) {
    const Tri t = mesh.faces[f];
    const int v = mesh.num_vertices();
    mesh.positions.push_back(l[0] * mesh.positions[t[0]] + l[1] * mesh.positions[t[1]] + l[2] * mesh.positions[t[2]]);
    mesh.site.push_back({-1, -1});
    std::map<int, FaceEdit> edits;
    int zero = -1;
    for (int k = 0; k < 3; ++k)
        if (l[k] == 0) zero = k;
    if (zero < 0) {
        edits[f].inner_points.emplace_back(v, l);
    } else {
        // On the side opposite corner `zero`: split the edge in both of its faces.
        const int a = t[(zero + 1) % 3], b = t[(zero + 2) % 3];
        const double s = l[(zero + 2) % 3] / (l[(zero + 1) % 3] + l[(zero + 2) % 3]);
        mesh.positions.back() = mesh.positions[a] + s * (mesh.positions[b] - mesh.positions[a]);
        mesh.site.back() = mesh.edge_site(a, b);
        for (int g : mesh.edge_faces.at(mesh.find_edge(a, b)))
            if (g >= 0) edits[g].edge_points.push_back({v, a, b, s});
    }
    apply_edits(mesh, edits);
    return v;
}

}  // namespace ctmap

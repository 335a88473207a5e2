#include "ctmap/cut/straighten_path.h"

#include <algorithm>
#include <unordered_map>

#include "ctmap/cut/face_frame.h"
#include "ctmap/errors.h"

namespace ctmap {
namespace {

using face_frame::CDT;
using face_frame::K;
using Point = K::Point_2;

/// The cell of the run: the faces of input face F reachable from the run's vertices without
/// crossing a path (another's, or this one's outside the run) or a side of F; `outline` holds the
/// edges where the flood stopped (none touches the run).
struct Cell {
    std::vector<int> faces, vertices;
    std::vector<std::pair<int, int>> outline;
};

Cell cell_of(const WorkMesh& m, const std::unordered_set<int>& run, int F,
             const std::unordered_set<std::uint64_t>& path_edges, const std::unordered_set<std::uint64_t>& own_edges) {
    Cell c;
    std::unordered_set<int> seen_face, seen_vertex;
    std::vector<int> stack;
    for (int v : run)
        for (int f : m.vertex_faces[v])
            if (seen_face.insert(f).second) stack.push_back(f);
    while (!stack.empty()) {
        const int f = stack.back();
        stack.pop_back();
        c.faces.push_back(f);
        for (int k = 0; k < 3; ++k) {
            const int a = m.faces[f][k], b = m.faces[f][(k + 1) % 3];
            if (seen_vertex.insert(a).second) c.vertices.push_back(a);
            const auto& ef = m.edge_faces[m.face_edges[f][k]];
            const int g = ef[0] == f ? ef[1] : ef[0];
            const std::uint64_t key = edge_key(a, b);
            const bool stop = g < 0 || m.origin[g] != F || path_edges.count(key) ||
                              (own_edges.count(key) && !run.count(a) && !run.count(b));
            if (stop) c.outline.emplace_back(a, b);
            else if (seen_face.insert(g).second) stack.push_back(g);
        }
    }
    return c;
}

/// Vertex `u` in the affine frame of input face `F` (face_frame.h): corners exact, points on a
/// side exactly on it, inner points by least squares in F's plane.
Point frame_of(const WorkMesh& m, int F, int u) {
    const Tri& t = m.input_faces[F];
    const auto site = m.site[u];
    const Vec3 &A = m.positions[t[0]], &B = m.positions[t[1]], &C = m.positions[t[2]];
    if (site[0] >= 0 && site[0] == site[1]) {
        for (int k = 0; k < 3; ++k)
            if (t[k] == site[0]) return face_frame::side_point(k, 0.0);
        throw InternalError("straighten_path: a vertex of an input face is not one of its corners");
    }
    if (site[0] >= 0) {
        for (int k = 0; k < 3; ++k) {
            const int a = t[k], b = t[(k + 1) % 3];
            if (std::min(a, b) != site[0] || std::max(a, b) != site[1]) continue;
            const Vec3 d = m.positions[b] - m.positions[a];
            const double s = std::clamp((m.positions[u] - m.positions[a]).dot(d) / d.squaredNorm(), 0.0, 1.0);
            return face_frame::side_point(k, s);
        }
        throw InternalError("straighten_path: a vertex on an input edge is not on a side of its face");
    }
    // P = A + x (B - A) + y (C - B), in the plane of the face.
    const Vec3 e1 = B - A, e2 = C - B, d = m.positions[u] - A;
    const double a11 = e1.dot(e1), a12 = e1.dot(e2), a22 = e2.dot(e2), b1 = e1.dot(d), b2 = e2.dot(d);
    const double det = a11 * a22 - a12 * a12;
    return {(b1 * a22 - b2 * a12) / det, (a11 * b2 - a12 * b1) / det};
}

/// Replaces the run `poly[1 .. size-2]` of a path by the segment poly.front() - poly.back()
/// inside input face F and re-triangulates the run's cell, if nothing is in the way
/// (straighten_path's rules).
bool straighten_run(WorkMesh& m, const std::vector<int>& poly, const std::vector<char>& blocked,
                    const std::unordered_set<std::uint64_t>& path_edges,
                    const std::unordered_set<std::uint64_t>& own_edges) {
    const int p = poly.front(), n = poly.back();
    if (m.edge_site(p, n)[0] >= 0) return false;  // both on one side of F: the segment would run along it
    const int F = m.origin[m.vertex_faces[poly[1]].front()];
    const std::unordered_set<int> run(poly.begin() + 1, poly.end() - 1);
    const Cell cell = cell_of(m, run, F, path_edges, own_edges);
    std::unordered_map<int, Point> at;
    for (int u : cell.vertices) at[u] = frame_of(m, F, u);
    const Point P = at.at(p), N = at.at(n);
    for (int u : cell.vertices) {
        if (u == p || u == n || run.count(u)) continue;
        const Point& w = at[u];
        if ((CGAL::collinear(P, w, N) && CGAL::collinear_are_strictly_ordered_along_line(P, w, N)) || w == P || w == N)
            return false;
        if (u >= int(blocked.size()) || !blocked[u]) continue;
        // A blocked vertex between the run and the segment: the path would change sides of it.
        for (std::size_t i = 1; i + 2 < poly.size(); ++i) {
            const Point &a = at.at(poly[i]), &b = at.at(poly[i + 1]);
            if (CGAL::orientation(P, a, b) == CGAL::COLLINEAR) continue;
            if (K::Triangle_2(P, a, b).bounded_side(w) != CGAL::ON_UNBOUNDED_SIDE) return false;
        }
    }
    CDT cdt;
    std::unordered_map<int, CDT::Vertex_handle> handle;
    for (int u : cell.vertices) {
        if (run.count(u)) continue;
        CDT::Vertex_handle h = cdt.insert(at[u]);
        h->info() = u;
        handle[u] = h;
    }
    if (cdt.number_of_vertices() != handle.size()) return false;  // two points coincide in the frame
    for (const auto& [a, b] : cell.outline) cdt.insert_constraint(handle.at(a), handle.at(b));
    cdt.insert_constraint(handle.at(p), handle.at(n));
    if (cdt.number_of_vertices() != handle.size()) return false;  // the segment crossed the outline
    if (!cdt.is_edge(handle.at(p), handle.at(n))) return false;
    for (const auto& [a, b] : cell.outline)
        if (!cdt.is_edge(handle.at(a), handle.at(b))) return false;
    // The cell: the faces not reached from outside the convex hull without crossing a constraint.
    std::unordered_set<CDT::Face_handle> outside;
    std::vector<CDT::Face_handle> stack;
    for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f)
        if (cdt.is_infinite(f) && outside.insert(f).second) stack.push_back(f);
    while (!stack.empty()) {
        const CDT::Face_handle f = stack.back();
        stack.pop_back();
        for (int k = 0; k < 3; ++k) {
            const CDT::Face_handle g = f->neighbor(k);
            if (!f->is_constrained(k) && outside.insert(g).second) stack.push_back(g);
        }
    }
    std::vector<Tri> added;
    std::unordered_set<int> covered;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
        if (outside.count(f)) continue;
        added.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
        for (int k = 0; k < 3; ++k) covered.insert(f->vertex(k)->info());
    }
    if (covered.size() != handle.size()) return false;  // a vertex of the cell outside it: something is amiss
    m.replace_faces(cell.faces, added, std::vector<int>(added.size(), F));
    return true;
}

}  // namespace

std::vector<int> straighten_path(WorkMesh& mesh, const std::vector<int>& chain, int first_new,
                                 const std::vector<char>& blocked, const std::unordered_set<std::uint64_t>& path_edges,
                                 StraightenStats* stats) {
    auto removable = [&](int v) { return v >= first_new && mesh.site[v][0] < 0; };
    std::vector<int> out = chain;
    // The path's own edges (straighten_run skips those at the run's vertices).
    std::unordered_set<std::uint64_t> own;
    for (std::size_t k = 0; k + 1 < out.size(); ++k) own.insert(edge_key(out[k], out[k + 1]));
    std::size_t i = 1;
    while (i + 1 < out.size()) {
        if (!removable(out[i])) {
            ++i;
            continue;
        }
        std::size_t j = i;
        while (j + 1 < out.size() && removable(out[j])) ++j;
        // out[i .. j-1] lie inside one input face (an edge between two of its inner points
        // cannot leave it); out[i-1] and out[j] lie in it or on its sides.
        const std::vector<int> poly(out.begin() + long(i) - 1, out.begin() + long(j) + 1);
        if (straighten_run(mesh, poly, blocked, path_edges, own)) {
            own.insert(edge_key(poly.front(), poly.back()));
            if (stats) stats->removed_vertices += int(j - i);
            out.erase(out.begin() + long(i), out.begin() + long(j));
            ++i;
        } else {
            if (stats) ++stats->kept_runs;
            i = j;
        }
    }
    return out;
}

}  // namespace ctmap

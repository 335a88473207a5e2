#include "ctmap/morph/common_mesh.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "ctmap/certify/certificate.h"
#include "ctmap/errors.h"
#include "ctmap/morph/locate_2d.h"

namespace ctmap {
namespace {

using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, EK>;
using Fb = CGAL::Constrained_triangulation_face_base_2<EK>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Overlay = CGAL::Constrained_Delaunay_triangulation_2<EK, Tds, CGAL::Exact_intersections_tag>;

/// The point of `mesh` where `l` says.
Vec3 surface_point(const TriMesh& mesh, const Location& l) {
    const Tri& t = mesh.faces[l.face];
    if (l.corner >= 0) return mesh.positions[t[l.corner]];
    return l.bary[0] * mesh.positions[t[0]] + l.bary[1] * mesh.positions[t[1]] + l.bary[2] * mesh.positions[t[2]];
}

/// +1 if the map's triangles are counter-clockwise, -1 if clockwise (a mirrored map).
int map_orientation(const std::vector<Vec2>& uv, const std::vector<Tri>& faces) {
    for (const Tri& t : faces)
        if (const int o = orientation_2d(uv[t[0]], uv[t[1]], uv[t[2]]); o != 0) return o;
    return 1;
}

double uv_area(const Vec2& a, const Vec2& b, const Vec2& c) {
    return 0.5 * std::abs((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

/// How many faces each undirected edge of `faces` has.
std::map<std::pair<int, int>, int> edge_faces(const std::vector<Tri>& faces) {
    std::map<std::pair<int, int>, int> count;
    for (const Tri& t : faces)
        for (int k = 0; k < 3; ++k) ++count[{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])}];
    return count;
}

/// Each edge of `faces` with two faces (interior), once.
std::vector<std::pair<int, int>> interior_edges(const std::vector<Tri>& faces) {
    std::vector<std::pair<int, int>> out;
    for (const auto& [e, n] : edge_faces(faces))
        if (n == 2) out.push_back(e);
    return out;
}

/// The vertices on the border of `faces` (ends of edges with one face).
std::vector<int> border_vertices(const std::vector<Tri>& faces) {
    std::set<int> out;
    for (const auto& [e, n] : edge_faces(faces))
        if (n == 1) out.insert({e.first, e.second});
    return {out.begin(), out.end()};
}

}  // namespace

CommonMesh common_mesh(const PlanarMap& source, const PlanarMap& target, const CommonMeshOptions& options) {
    const TriMesh& S = *source.mesh;
    const TriMesh& T = *target.mesh;
    const std::vector<Vec2>& suv = *source.uv;
    const std::vector<Vec2>& tuv = *target.uv;
    CommonMesh out;
    out.source_vertices = S.num_vertices();
    const TriangleLocator in_target(tuv, T.faces);
    auto on_target = [&](const Vec2& p) {
        const Location l = in_target.locate(p);
        out.outside += !l.inside;
        return surface_point(T, l);
    };
    if (!options.insert_target_vertices) {  // the source's connectivity only
        out.mesh = S;
        out.uv = suv;
        for (const Vec2& p : suv) out.target_position.push_back(on_target(p));
        return out;
    }

    // The overlay: both maps' vertices and edges in one constrained triangulation of the domain,
    // with exact intersections. Each of its triangles lies in one source and one target triangle,
    // so it is flat on both surfaces.
    Overlay overlay;
    std::vector<Overlay::Vertex_handle> source_vh(suv.size()), target_vh(tuv.size());
    for (std::size_t v = 0; v < suv.size(); ++v) {
        source_vh[v] = overlay.insert(EK::Point_2(suv[v].x(), suv[v].y()));
        source_vh[v]->info() = int(v);
    }
    int next = S.num_vertices();
    const std::set<Overlay::Vertex_handle> from_source(source_vh.begin(), source_vh.end());
    for (std::size_t v = 0; v < tuv.size(); ++v) {
        target_vh[v] = overlay.insert(EK::Point_2(tuv[v].x(), tuv[v].y()));
        if (from_source.count(target_vh[v])) {
            ++out.merged;  // a source vertex's point: shared
        } else {
            target_vh[v]->info() = next++;
            ++out.inserted;
        }
    }
    // The vertices made by constraint intersections are the others (their info is not set yet).
    std::set<Overlay::Vertex_handle> known(source_vh.begin(), source_vh.end());
    known.insert(target_vh.begin(), target_vh.end());
    // Both borders lie on the same polygon's sides, each up to rounding: as two chains they would
    // cross each other at every rounding. One chain of both borders' vertices in turn around the
    // domain's centre (the polygon is convex) bounds the overlay instead.
    std::set<std::pair<Overlay::Vertex_handle, Overlay::Vertex_handle>> chain;
    {
        std::vector<std::pair<double, Overlay::Vertex_handle>> around;
        Vec2 centre(0, 0);
        for (const Vec2& p : suv) centre += p;
        centre /= double(std::max<std::size_t>(1, suv.size()));
        for (int v : border_vertices(S.faces)) around.emplace_back(std::atan2(suv[v].y() - centre.y(), suv[v].x() - centre.x()), source_vh[v]);
        for (int v : border_vertices(T.faces)) around.emplace_back(std::atan2(tuv[v].y() - centre.y(), tuv[v].x() - centre.x()), target_vh[v]);
        std::sort(around.begin(), around.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
        around.erase(std::unique(around.begin(), around.end(), [](const auto& a, const auto& b) { return a.second == b.second; }),
                     around.end());
        for (std::size_t k = 0; k < around.size(); ++k) {
            const auto a = around[k].second, b = around[(k + 1) % around.size()].second;
            if (a == b) continue;
            overlay.insert_constraint(a, b);
            chain.emplace(std::min(a, b), std::max(a, b));
        }
    }
    for (auto [a, b] : interior_edges(S.faces)) overlay.insert_constraint(source_vh[a], source_vh[b]);
    for (auto [a, b] : interior_edges(T.faces)) overlay.insert_constraint(target_vh[a], target_vh[b]);
    std::vector<Overlay::Vertex_handle> crossing;
    for (auto v = overlay.finite_vertices_begin(); v != overlay.finite_vertices_end(); ++v)
        if (!known.count(v)) {
            v->info() = next++;
            crossing.push_back(v);
        }
    out.crossings = int(crossing.size());

    // Positions: each vertex on the source surface and on the target surface.
    const TriangleLocator in_source(suv, S.faces);
    out.mesh.positions.resize(std::size_t(next));
    out.target_position.resize(std::size_t(next));
    out.uv.resize(std::size_t(next));
    for (auto v = overlay.finite_vertices_begin(); v != overlay.finite_vertices_end(); ++v) {
        const int i = v->info();
        const Vec2 p(CGAL::to_double(v->point().x()), CGAL::to_double(v->point().y()));
        out.uv[i] = i < S.num_vertices() ? suv[i] : p;
        if (i < S.num_vertices()) {
            out.mesh.positions[i] = S.positions[i];
        } else {
            const Location l = in_source.locate(p);
            out.outside += !l.inside;
            out.mesh.positions[i] = surface_point(S, l);
        }
    }
    for (std::size_t v = 0; v < tuv.size(); ++v) out.target_position[target_vh[v]->info()] = T.positions[v];
    std::vector<bool> from_target(std::size_t(next), false);
    for (const auto& vh : target_vh) from_target[vh->info()] = true;
    for (auto v = overlay.finite_vertices_begin(); v != overlay.finite_vertices_end(); ++v)
        if (!from_target[v->info()]) out.target_position[v->info()] = on_target(out.uv[v->info()]);

    // Faces inside the border chain: those not reached from outside without crossing it.
    std::set<Overlay::Face_handle> outside;
    std::vector<Overlay::Face_handle> stack;
    auto incident = overlay.incident_faces(overlay.infinite_vertex()), done = incident;
    do {
        if (outside.insert(incident).second) stack.push_back(incident);
    } while (++incident != done);
    while (!stack.empty()) {
        const Overlay::Face_handle f = stack.back();
        stack.pop_back();
        for (int i = 0; i < 3; ++i) {
            const auto a = f->vertex(Overlay::cw(i)), b = f->vertex(Overlay::ccw(i));
            if (chain.count({std::min(a, b), std::max(a, b)})) continue;
            const Overlay::Face_handle g = f->neighbor(i);
            if (outside.insert(g).second) stack.push_back(g);
        }
    }
    const bool flip = map_orientation(suv, S.faces) < 0;  // turned to the source's orientation
    double kept = 0;
    for (auto f = overlay.finite_faces_begin(); f != overlay.finite_faces_end(); ++f) {
        if (outside.count(f)) continue;
        const int a = f->vertex(0)->info(), b = f->vertex(1)->info(), d = f->vertex(2)->info();
        out.mesh.faces.push_back(flip ? Tri{a, d, b} : Tri{a, b, d});
        kept += uv_area(out.uv[a], out.uv[b], out.uv[d]);
    }
    // The kept faces cover the source's domain once (a chain edge split by CGAL would let the
    // outside fill leak inside and drop faces): say so rather than return a mesh with holes.
    double domain = 0;
    for (const Tri& t : S.faces) domain += uv_area(suv[t[0]], suv[t[1]], suv[t[2]]);
    if (!(std::abs(kept - domain) <= 1e-6 * domain))
        throw InternalError("common mesh: the overlay's faces cover " + std::to_string(kept) + " of the domain's " +
                            std::to_string(domain) + " (UV area)");
    return out;
}

}  // namespace ctmap

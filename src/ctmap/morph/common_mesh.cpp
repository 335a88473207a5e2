#include "ctmap/morph/common_mesh.h"

#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <map>

#include "ctmap/certify/certificate.h"
#include "ctmap/morph/locate_2d.h"

namespace ctmap {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb>;
using Delaunay = CGAL::Delaunay_triangulation_2<K, Tds>;

/// A point on a source edge (u < v): its parameter from u to v and its common-mesh vertex.
struct EdgePoint {
    double s;
    int vertex;
};

/// The point of reference triangle (0,0), (1,0), (0,1) at parameter s along its edge from corner
/// a to corner b. On the hypotenuse the coordinate >= 1/2 is kept and the other is 1 minus it,
/// exact by Sterbenz's lemma, so the point lies exactly on the hypotenuse.
K::Point_2 on_reference_edge(int a, int b, double s) {
    static const double corner[3][2] = {{0, 0}, {1, 0}, {0, 1}};
    if (a + b == 3) {  // corners 1 and 2
        double x = a == 1 ? 1 - s : s;  // x-coordinate of the point
        if (x >= 0.5) return {x, 1 - x};
        const double y = 1 - x;
        return {1 - y, y};
    }
    const double x = corner[a][0] + s * (corner[b][0] - corner[a][0]);
    const double y = corner[a][1] + s * (corner[b][1] - corner[a][1]);
    return {x, y};
}

}  // namespace

CommonMesh common_mesh(const PlanarMap& source, const PlanarMap& target, const CommonMeshOptions& options) {
    const TriMesh& S = *source.mesh;
    const TriMesh& T = *target.mesh;
    const std::vector<Vec2>& suv = *source.uv;
    const std::vector<Vec2>& tuv = *target.uv;
    CommonMesh out;
    out.source_vertices = S.num_vertices();
    out.mesh.positions = S.positions;
    out.uv = suv;
    out.target_position.resize(S.positions.size());

    // Every source vertex on the target surface.
    const TriangleLocator in_target(tuv, T.faces);
    for (int v = 0; v < S.num_vertices(); ++v) {
        const Location l = in_target.locate(suv[v]);
        const Tri& t = T.faces[l.face];
        out.target_position[v] = l.corner >= 0 ? T.positions[t[l.corner]]
                                               : Vec3(l.bary[0] * T.positions[t[0]] + l.bary[1] * T.positions[t[1]] +
                                                      l.bary[2] * T.positions[t[2]]);
        out.outside += !l.inside;
    }
    if (!options.insert_target_vertices) {
        out.mesh.faces = S.faces;
        return out;
    }

    // Every target vertex in the source's faces: a corner (shared), on an edge, or inside.
    const TriangleLocator in_source(suv, S.faces);
    std::map<std::pair<int, int>, std::vector<EdgePoint>> on_edge;
    std::vector<std::vector<std::pair<Vec2, int>>> inside(S.faces.size());  // reference coordinates, vertex
    auto add_vertex = [&](int f, const Vec3& b, int tv) {
        const Tri& t = S.faces[f];
        out.mesh.positions.push_back(b[0] * S.positions[t[0]] + b[1] * S.positions[t[1]] + b[2] * S.positions[t[2]]);
        out.uv.push_back(b[0] * suv[t[0]] + b[1] * suv[t[1]] + b[2] * suv[t[2]]);
        out.target_position.push_back(T.positions[tv]);
        ++out.inserted;
        return out.mesh.num_vertices() - 1;
    };
    for (int tv = 0; tv < T.num_vertices(); ++tv) {
        const Location l = in_source.locate(tuv[tv]);
        out.outside += !l.inside;
        const Tri& t = S.faces[l.face];
        Vec3 b = l.bary;
        if (l.corner < 0) {
            // On an edge when the exact orientation with it is zero (or rounding put it outside).
            for (int k = 0; k < 3; ++k) {
                const int i = (k + 1) % 3, j = (k + 2) % 3;
                const int o = orientation_2d(suv[t[i]], suv[t[j]], tuv[tv]) *
                              orientation_2d(suv[t[i]], suv[t[j]], suv[t[k]]);
                if (o <= 0 || b[k] == 0) b[k] = 0;
            }
            b /= b.sum();
        }
        // Strictly inside in UV may still round onto the hypotenuse of the reference frame.
        if (b[0] != 0 && CGAL::orientation(K::Point_2(1, 0), K::Point_2(0, 1), K::Point_2(b[1], b[2])) != CGAL::LEFT_TURN) {
            b[0] = 0;
            b /= b.sum();
        }
        const int zeros = int(b[0] == 0) + int(b[1] == 0) + int(b[2] == 0);
        if (l.corner >= 0 || zeros >= 2) {  // the source vertex's point: it takes the target vertex
            const int k = l.corner >= 0 ? l.corner : int(b[0] != 0 ? 0 : b[1] != 0 ? 1 : 2);
            out.target_position[t[k]] = T.positions[tv];
            ++out.merged;
            continue;
        }
        if (zeros == 1) {
            const int k = b[0] == 0 ? 0 : b[1] == 0 ? 1 : 2;
            const int u = t[(k + 1) % 3], v = t[(k + 2) % 3];
            const double s_uv = b[(k + 2) % 3];  // parameter from u to v
            const double s = u < v ? s_uv : 1 - s_uv;
            on_edge[{std::min(u, v), std::max(u, v)}].push_back({s, add_vertex(l.face, b, tv)});
            continue;
        }
        inside[l.face].emplace_back(Vec2(b[1], b[2]), add_vertex(l.face, b, tv));
    }
    for (auto& [edge, points] : on_edge) {
        std::sort(points.begin(), points.end(), [](const EdgePoint& a, const EdgePoint& b) { return a.s < b.s; });
    }

    // Faces with no point keep their triangle; the others are triangulated in their reference frame.
    for (int f = 0; f < S.num_faces(); ++f) {
        const Tri& t = S.faces[f];
        std::vector<std::pair<K::Point_2, int>> points;
        for (int k = 0; k < 3; ++k) {
            const int u = t[k], v = t[(k + 1) % 3];
            auto it = on_edge.find({std::min(u, v), std::max(u, v)});
            if (it == on_edge.end()) continue;
            for (const EdgePoint& p : it->second) {
                const double s = u < v ? p.s : 1 - p.s;  // from corner k to corner k+1
                points.emplace_back(on_reference_edge(k, (k + 1) % 3, s), p.vertex);
            }
        }
        if (points.empty() && inside[f].empty()) {
            out.mesh.faces.push_back(t);
            continue;
        }
        points.emplace_back(K::Point_2(0, 0), t[0]);
        points.emplace_back(K::Point_2(1, 0), t[1]);
        points.emplace_back(K::Point_2(0, 1), t[2]);
        for (const auto& [q, v] : inside[f]) points.emplace_back(K::Point_2(q.x(), q.y()), v);
        Delaunay dt;
        dt.insert(points.begin(), points.end());
        for (auto fit = dt.finite_faces_begin(); fit != dt.finite_faces_end(); ++fit)
            out.mesh.faces.push_back({fit->vertex(0)->info(), fit->vertex(1)->info(), fit->vertex(2)->info()});
    }
    return out;
}

}  // namespace ctmap

#include "ctmap/io/triangulate_polygon.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <deque>
#include <tuple>

#include "ctmap/errors.h"

namespace ctmap {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

/// Newell's normal of a polygon: robust for non-planar and non-convex polygons.
Vec3 newell_normal(const std::vector<Vec3>& p) {
    Vec3 n = Vec3::Zero();
    for (std::size_t i = 0; i < p.size(); ++i) n += p[i].cross(p[(i + 1) % p.size()]);
    return n;
}

/// A large polygon projected on its Newell plane and triangulated by a constrained Delaunay
/// triangulation; the faces inside are found by their nesting depth from the outside. Returns
/// corner indices into `corners`, or nothing if the projection is not a simple polygon.
std::vector<std::array<int, 3>> planar_triangulation(const std::vector<Vec3>& corners, const Vec3& normal) {
    using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
    using Fb = CGAL::Triangulation_face_base_with_info_2<int, K, CGAL::Constrained_triangulation_face_base_2<K>>;
    using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
    using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;
    const Vec3 n = normal.normalized();
    const Vec3 u = n.unitOrthogonal(), v = n.cross(u);
    CDT cdt;
    std::vector<CDT::Vertex_handle> vh;
    vh.reserve(corners.size());
    for (std::size_t i = 0; i < corners.size(); ++i) {
        vh.push_back(cdt.insert(K::Point_2(corners[i].dot(u), corners[i].dot(v))));
        vh.back()->info() = int(i);
    }
    if (cdt.number_of_vertices() != corners.size()) return {};  // two corners project to one point
    try {
        for (std::size_t i = 0; i < corners.size(); ++i) cdt.insert_constraint(vh[i], vh[(i + 1) % corners.size()]);
    } catch (const std::exception&) {  // two sides of the projected polygon cross
        return {};
    }
    if (cdt.number_of_vertices() != corners.size()) return {};  // a side passes through a corner
    for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
    // Nesting depth: 0 outside; crossing a constraint adds one. Inside a simple polygon: 1.
    std::deque<std::pair<CDT::Face_handle, int>> queue{{cdt.infinite_face(), 0}};
    while (!queue.empty()) {
        auto [f, depth] = queue.front();
        queue.pop_front();
        if (f->info() != -1) continue;
        f->info() = depth;
        for (int k = 0; k < 3; ++k) {
            const CDT::Face_handle g = f->neighbor(k);
            if (g->info() != -1) continue;
            if (cdt.is_constrained(CDT::Edge(f, k))) queue.emplace_back(g, depth + 1);
            else queue.emplace_front(g, depth);
        }
    }
    std::vector<std::array<int, 3>> tris;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
        if (f->info() % 2 == 1) tris.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
    return tris;
}

}  // namespace

void triangulate_polygon(const std::string& path, std::size_t face_index, const std::vector<std::size_t>& poly,
                         const std::vector<Vec3>& positions, std::vector<Tri>& out) {
    if (poly.size() == 3) {
        out.push_back({int(poly[0]), int(poly[1]), int(poly[2])});
        return;
    }
    std::vector<Vec3> corners;
    for (std::size_t v : poly) corners.push_back(positions[v]);
    const Vec3 n = newell_normal(corners);
    std::vector<std::array<int, 3>> tris;
    const bool large = poly.size() > kMaxHoleFillingCorners;
    if (large) {
        if (n.squaredNorm() > 0) tris = planar_triangulation(corners, n);
    } else {
        std::vector<K::Point_3> ring;
        for (const Vec3& q : corners) ring.emplace_back(q.x(), q.y(), q.z());
        std::vector<std::tuple<int, int, int>> t;
        CGAL::Polygon_mesh_processing::triangulate_hole_polyline(ring, std::back_inserter(t));
        for (auto [a, b, c] : t) tris.push_back({a, b, c});
    }
    if (tris.size() != poly.size() - 2)
        throw BadInput(path, "face " + std::to_string(face_index) + " (a polygon with " + std::to_string(poly.size()) +
                                 " corners) could not be triangulated" +
                                 (large ? " (a polygon this large must be simple in its plane)" : ""));
    // Neither method promises the polygon's orientation: follow the polygon's normal.
    for (const auto& [a, b, c] : tris) {
        Tri t{int(poly[a]), int(poly[b]), int(poly[c])};
        const Vec3 tn = (positions[t[1]] - positions[t[0]]).cross(positions[t[2]] - positions[t[0]]);
        if (tn.dot(n) < 0) std::swap(t[1], t[2]);
        out.push_back(t);
    }
}

}  // namespace ctmap

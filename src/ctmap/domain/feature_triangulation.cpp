#include "ctmap/domain/feature_triangulation.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <algorithm>
#include <map>
#include <set>

#include "ctmap/errors.h"
#include "ctmap/io/printable.h"

namespace ctmap {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using P2 = K::Point_2;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<int, K>;
struct FaceInfo {
    int nesting = -1;
    bool inside() const { return nesting % 2 == 1; }
};
using Fbi = CGAL::Triangulation_face_base_with_info_2<FaceInfo, K>;
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CDT = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;

/// Marks faces by how many constraint edges separate them from the outside (CGAL's
/// polygon-with-holes idiom): odd nesting = inside the border polygon.
void mark_domains(CDT& cdt) {
    for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info().nesting = -1;
    std::vector<CDT::Face_handle> queue{cdt.infinite_face()};
    std::vector<CDT::Edge> border;
    int level = 0;
    while (!queue.empty()) {
        while (!queue.empty()) {
            CDT::Face_handle f = queue.back();
            queue.pop_back();
            if (f->info().nesting != -1) continue;
            f->info().nesting = level;
            for (int i = 0; i < 3; ++i) {
                CDT::Face_handle n = f->neighbor(i);
                if (n->info().nesting != -1) continue;
                if (cdt.is_constrained(CDT::Edge(f, i))) border.emplace_back(f, i);
                else queue.push_back(n);
            }
        }
        ++level;
        for (const CDT::Edge& e : border) {
            CDT::Face_handle n = e.first->neighbor(e.second);
            if (n->info().nesting == -1) queue.push_back(n);
        }
        border.clear();
    }
}

}  // namespace

std::string feature_label(const std::vector<std::string>& names, int i) {
    return i < int(names.size()) && !names[i].empty() ? quoted_name(names[i]) : "#" + std::to_string(i);
}

FeatureTriangulation triangulate_features(const std::vector<Vec2>& uv, const std::vector<int>& border,
                                          const std::vector<std::string>& names, const TriangulateOptions& /*options*/) {
    const int n = int(uv.size());
    if (border.size() < 3)
        throw BadInput("", "only " + std::to_string(border.size()) +
                                 " feature(s) lie on the mesh border; at least 3 border features are needed "
                                 "to fix the map's border");
    std::vector<char> on_border(n, 0);
    for (int b : border) on_border.at(b) = 1;

    // Simplicity of the border polygon with exact predicates (m is small: O(m^2) is fine). A
    // crossing means the features' order in the image differs from their order on the mesh.
    // (Mirroring keeps crossings, so the check runs on the image's own points.)
    std::vector<P2> poly;
    for (int b : border) poly.emplace_back(uv[b].x(), uv[b].y());
    const int m = int(border.size());
    for (int i = 0; i < m; ++i)
        for (int j = i + 1; j < m; ++j) {
            const int i2 = (i + 1) % m, j2 = (j + 1) % m;
            const K::Segment_2 a(poly[i], poly[i2]), b(poly[j], poly[j2]);
            const bool adjacent = i2 == j || j2 == i;
            bool bad = false;
            if (!adjacent) bad = CGAL::do_intersect(a, b);
            else {
                // Adjacent edges may only share their common corner: fail if they fold back.
                const P2& shared = i2 == j ? poly[i2] : poly[i];
                const P2& pa = i2 == j ? poly[i] : poly[i2];
                const P2& pb = i2 == j ? poly[j2] : poly[j];
                bad = CGAL::collinear(pa, shared, pb) && !CGAL::collinear_are_ordered_along_line(pa, shared, pb);
            }
            if (bad)
                throw BadInput("", "the border features' order in the image does not match their order along the "
                                     "mesh border: border edges " +
                                         feature_label(names, border[i]) + "-" + feature_label(names, border[i2]) + " and " +
                                         feature_label(names, border[j]) + "-" + feature_label(names, border[j2]) +
                                         " cross in the image");
        }

    // The image border must run the same way round as the mesh border (counter-clockwise in UV),
    // or the opposite way (a mirrored chart). Work in the mesh's sense: mirror x when needed.
    // (CGAL's orientation_2 needs a simple polygon: the check above comes first.)
    const bool mirrored = CGAL::orientation_2(poly.begin(), poly.end(), K()) == CGAL::CLOCKWISE;
    std::vector<P2> pts(n);
    for (int i = 0; i < n; ++i) pts[i] = P2(mirrored ? -uv[i].x() : uv[i].x(), uv[i].y());
    poly.clear();
    for (int b : border) poly.push_back(pts[b]);

    std::vector<std::string> outside;
    for (int i = 0; i < n; ++i) {
        if (on_border[i]) continue;
        const auto side = CGAL::bounded_side_2(poly.begin(), poly.end(), pts[i], K());
        if (side != CGAL::ON_BOUNDED_SIDE) outside.push_back(feature_label(names, i) + (side == CGAL::ON_BOUNDARY ? " (on it)" : ""));
    }
    if (!outside.empty()) {
        std::string list;
        for (const auto& s : outside) list += (list.empty() ? "" : ", ") + s;
        throw BadInput("", "interior feature(s) outside the border polygon in the image: " + list +
                                 " (a feature inside the mesh must lie inside the polygon of the border features)");
    }

    CDT cdt;
    std::vector<CDT::Vertex_handle> vh(n);
    for (int i = 0; i < n; ++i) {
        vh[i] = cdt.insert(pts[i]);
        vh[i]->info() = i;
    }
    for (int i = 0; i < m; ++i) cdt.insert_constraint(vh[border[i]], vh[border[(i + 1) % m]]);
    if (int(cdt.number_of_vertices()) != n)
        throw InternalError("the feature triangulation gained or lost vertices (constraints intersect)");
    mark_domains(cdt);

    FeatureTriangulation ft;
    ft.points = uv;
    ft.border = border;
    ft.mirrored = mirrored;
    std::set<std::array<int, 2>> edges;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
        if (!f->info().inside()) continue;
        const Tri t{f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()};
        ft.triangles.push_back(t);
        for (int k = 0; k < 3; ++k) edges.insert({std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])});
    }
    std::set<std::array<int, 2>> border_edges;
    for (int i = 0; i < m; ++i)
        border_edges.insert({std::min(border[i], border[(i + 1) % m]), std::max(border[i], border[(i + 1) % m])});
    for (const auto& e : edges) {
        ft.edges.push_back(e);
        ft.edge_on_border.push_back(border_edges.count(e) > 0);
    }

    // Neighbours counter-clockwise (mesh sense) around each feature, restricted to kept edges.
    std::vector<int> next_on_border(n, -1);
    for (int i = 0; i < m; ++i) next_on_border[border[i]] = border[(i + 1) % m];
    ft.neighbours.assign(n, {});
    for (int i = 0; i < n; ++i) {
        std::vector<int> ring;
        auto c = cdt.incident_vertices(vh[i]), done = c;
        do {
            if (!cdt.is_infinite(c)) ring.push_back(c->info());
        } while (++c != done);
        std::vector<int> kept;
        for (int w : ring)
            if (edges.count({std::min(i, w), std::max(i, w)})) kept.push_back(w);
        if (on_border[i]) {
            // Start at the next border feature: the interior then follows counter-clockwise.
            auto it = std::find(kept.begin(), kept.end(), next_on_border[i]);
            std::rotate(kept.begin(), it, kept.end());
        }
        ft.neighbours[i] = kept;
    }
    return ft;
}

}  // namespace ctmap

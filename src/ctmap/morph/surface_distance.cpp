#include "ctmap/morph/surface_distance.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "ctmap/errors.h"

namespace ctmap {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Triangles = std::vector<K::Triangle_3>;
using Primitive = CGAL::AABB_triangle_primitive<K, Triangles::const_iterator>;
using Traits = CGAL::AABB_traits<K, Primitive>;
K::Point_3 point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
}  // namespace

struct SurfaceDistance::Tree {
    Triangles triangles;
    CGAL::AABB_tree<Traits> tree;
};

SurfaceDistance::SurfaceDistance(const TriMesh& mesh) : tree_(std::make_unique<Tree>()) {
    for (const Tri& t : mesh.faces) {
        const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
        if ((b - a).cross(c - a).norm() > 0) tree_->triangles.emplace_back(point(a), point(b), point(c));
    }
    if (tree_->triangles.empty()) throw BadInput("", "the surface has no face of nonzero area");
    tree_->tree.insert(tree_->triangles.begin(), tree_->triangles.end());
    tree_->tree.build();
    tree_->tree.accelerate_distance_queries();
}

SurfaceDistance::~SurfaceDistance() = default;

double SurfaceDistance::distance(const Vec3& p) const { return std::sqrt(tree_->tree.squared_distance(point(p))); }

double hausdorff_from(const TriMesh& from, const TriMesh& to, int samples_per_face) {
    const SurfaceDistance d(to);
    double h = 0;
    for (const Vec3& p : from.positions) h = std::max(h, d.distance(p));
    // Fixed interior points per face (barycentric), besides the centroid and edge midpoints.
    static const double pattern[][3] = {{0.6, 0.2, 0.2}, {0.2, 0.6, 0.2}, {0.2, 0.2, 0.6}, {0.45, 0.45, 0.1},
                                        {0.1, 0.45, 0.45}, {0.45, 0.1, 0.45}};
    for (const Tri& t : from.faces) {
        const Vec3 &a = from.positions[t[0]], &b = from.positions[t[1]], &c = from.positions[t[2]];
        h = std::max({h, d.distance((a + b + c) / 3), d.distance(0.5 * (a + b)), d.distance(0.5 * (b + c)),
                      d.distance(0.5 * (c + a))});
        for (int k = 0; k < std::min(samples_per_face, 6); ++k)
            h = std::max(h, d.distance(pattern[k][0] * a + pattern[k][1] * b + pattern[k][2] * c));
    }
    return h;
}

double mean_edge_length(const TriMesh& mesh) {
    std::set<std::pair<int, int>> seen;
    double sum = 0;
    for (const Tri& t : mesh.faces)
        for (int k = 0; k < 3; ++k) {
            const int u = t[k], v = t[(k + 1) % 3];
            if (seen.emplace(std::min(u, v), std::max(u, v)).second) sum += (mesh.positions[u] - mesh.positions[v]).norm();
        }
    return seen.empty() ? 0 : sum / double(seen.size());
}

}  // namespace ctmap

#include "ctmap/surface_locator.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <vector>

#include "ctmap/errors.h"

namespace ctmap {
namespace {
using LocatorKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using LocatorTriangles = std::vector<LocatorKernel::Triangle_3>;
using LocatorPrimitive = CGAL::AABB_triangle_primitive<LocatorKernel, LocatorTriangles::const_iterator>;
using LocatorTraits = CGAL::AABB_traits<LocatorKernel, LocatorPrimitive>;
LocatorKernel::Point_3 cgal_point(const Vec3& p) { return {p.x(), p.y(), p.z()}; }
}  // namespace

struct SurfaceLocator::Tree {
    LocatorTriangles triangles;
    std::vector<int> face;  ///< per triangle of the tree, its face of the mesh
    CGAL::AABB_tree<LocatorTraits> tree;
};

SurfaceLocator::SurfaceLocator(const TriMesh& mesh) : tree_(std::make_unique<Tree>()) {
    for (int f = 0; f < mesh.num_faces(); ++f) {
        const Tri& t = mesh.faces[f];
        const Vec3 &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
        if ((b - a).cross(c - a).norm() > 0) {
            tree_->triangles.emplace_back(cgal_point(a), cgal_point(b), cgal_point(c));
            tree_->face.push_back(f);
        }
    }
    if (tree_->triangles.empty()) throw BadInput("", "the surface has no face of nonzero area");
    tree_->tree.insert(tree_->triangles.begin(), tree_->triangles.end());
    tree_->tree.build();
    tree_->tree.accelerate_distance_queries();
    // One query now, so nothing is built lazily when threads query it at once.
    tree_->tree.closest_point(tree_->triangles.front().vertex(0));
}

SurfaceLocator::~SurfaceLocator() = default;

SurfacePoint SurfaceLocator::closest(const Vec3& p) const {
    const auto q = cgal_point(p);
    const auto hit = tree_->tree.closest_point_and_primitive(q);
    SurfacePoint out;
    out.face = tree_->face[std::size_t(hit.second - tree_->triangles.begin())];
    out.point = Vec3(hit.first.x(), hit.first.y(), hit.first.z());
    out.squared_distance = (out.point - p).squaredNorm();
    return out;
}

double SurfaceLocator::distance(const Vec3& p) const { return std::sqrt(tree_->tree.squared_distance(cgal_point(p))); }

}  // namespace ctmap

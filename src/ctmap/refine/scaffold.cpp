#include "ctmap/refine/scaffold.h"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

#include <deque>
#include <limits>

#include "ctmap/certify/certificate.h"
#include "ctmap/errors.h"
#include "ctmap/refine/box_barrier.h"
#include "ctmap/refine/flip_free_step.h"

namespace ctmap {
namespace {

using ScaffoldKernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using ScaffoldVb = CGAL::Triangulation_vertex_base_with_info_2<int, ScaffoldKernel>;
using ScaffoldFb = CGAL::Triangulation_face_base_with_info_2<int, ScaffoldKernel,
                                                             CGAL::Constrained_triangulation_face_base_2<ScaffoldKernel>>;
using ScaffoldCdt = CGAL::Constrained_Delaunay_triangulation_2<
    ScaffoldKernel, CGAL::Triangulation_data_structure_2<ScaffoldVb, ScaffoldFb>, CGAL::No_constraint_intersection_tag>;

}  // namespace

Scaffold::Scaffold(const std::vector<int>& loop, const std::vector<Vec2>& uv, Vec2 lo, Vec2 hi, double margin,
                   double area_ref, double weight)
    : nv_(int(uv.size())), area_ref_(area_ref), weight_(weight) {
    const Vec2 size = (hi - lo).cwiseMax(Vec2::Constant(1e-12 + 1e-9 * (hi - lo).norm()));
    const Vec2 a = lo - margin * size, b = hi + margin * size;
    constexpr int kSide = 5;  // points per side, the corner included
    for (int i = 0; i < kSide; ++i) {
        const double t = double(i) / kSide;
        frame_.emplace_back(a.x() + t * (b.x() - a.x()), a.y());
        frame_.emplace_back(b.x(), a.y() + t * (b.y() - a.y()));
        frame_.emplace_back(b.x() - t * (b.x() - a.x()), b.y());
        frame_.emplace_back(a.x(), b.y() - t * (b.y() - a.y()));
    }
    ScaffoldCdt cdt;
    std::vector<ScaffoldCdt::Vertex_handle> vh;
    vh.reserve(loop.size());
    for (int v : loop) {
        vh.push_back(cdt.insert(ScaffoldKernel::Point_2(uv[v].x(), uv[v].y())));
        vh.back()->info() = v;
    }
    for (std::size_t i = 0; i < frame_.size(); ++i)
        cdt.insert(ScaffoldKernel::Point_2(frame_[i].x(), frame_[i].y()))->info() = nv_ + int(i);
    if (cdt.number_of_vertices() != loop.size() + frame_.size())
        throw InternalError("scaffold: two border vertices of the map share a UV point");
    try {
        for (std::size_t i = 0; i < loop.size(); ++i) cdt.insert_constraint(vh[i], vh[(i + 1) % loop.size()]);
    } catch (const std::exception&) {
        throw InternalError("scaffold: the map's UV border is not simple");
    }
    if (cdt.number_of_vertices() != loop.size() + frame_.size())
        throw InternalError("scaffold: a border edge passes through a border vertex");
    // The scaffold: the finite faces reached from the outside without crossing the border.
    for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = 0;
    std::deque<ScaffoldCdt::Face_handle> queue{cdt.infinite_face()};
    cdt.infinite_face()->info() = 1;
    while (!queue.empty()) {
        const ScaffoldCdt::Face_handle f = queue.front();
        queue.pop_front();
        for (int k = 0; k < 3; ++k) {
            const ScaffoldCdt::Face_handle g = f->neighbor(k);
            if (g->info() != 0 || cdt.is_constrained({f, k})) continue;
            g->info() = 1;
            queue.push_back(g);
        }
    }
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
        if (f->info() != 1) continue;
        faces_.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
        const auto& t = faces_.back();
        const Vec2 e1 = at(t[1], uv) - at(t[0], uv), e2 = at(t[2], uv) - at(t[0], uv);
        area_ += 0.5 * (e1.x() * e2.y() - e1.y() * e2.x());
    }
}

namespace {

/// Twice the signed area of (a, b, c) and its gradient with respect to each corner.
double double_area(const Vec2& a, const Vec2& b, const Vec2& c, Vec2 g[3]) {
    const Vec2 q[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
        const Vec2& u = q[(k + 1) % 3];
        const Vec2& w = q[(k + 2) % 3];
        g[k] = Vec2(u.y() - w.y(), w.x() - u.x());
    }
    const Vec2 e1 = b - a, e2 = c - a;
    return e1.x() * e2.y() - e1.y() * e2.x();
}

}  // namespace

double Scaffold::energy(const std::vector<Vec2>& x) const {
    double e = 0;
    Vec2 g[3];
    for (const auto& t : faces_) {
        double phi, d1, d2;
        wall_barrier(0.5 * double_area(at(t[0], x), at(t[1], x), at(t[2], x), g), area_ref_, phi, d1, d2);
        e += weight_ * phi;
    }
    return e;
}

double Scaffold::max_step(const std::vector<Vec2>& x, const std::vector<Vec2>& d) const {
    double best = std::numeric_limits<double>::infinity();
    auto dir = [&](int k) { return k < nv_ ? d[k] : Vec2(0, 0); };
    for (const auto& t : faces_) {
        const Vec2 p0 = at(t[0], x), e1 = at(t[1], x) - p0, e2 = at(t[2], x) - p0;
        const Vec2 d0 = dir(t[0]), f1 = dir(t[1]) - d0, f2 = dir(t[2]) - d0;
        // twice the signed area of the moved triangle: c + b t + a t^2
        const double c = e1.x() * e2.y() - e1.y() * e2.x();
        const double b = e1.x() * f2.y() - e1.y() * f2.x() + f1.x() * e2.y() - f1.y() * e2.x();
        const double a = f1.x() * f2.y() - f1.y() * f2.x();
        if (!(c > 0)) return 0;
        best = std::min(best, smallest_positive_root(a, b, c));
    }
    return best;
}

bool Scaffold::exact_ok(const std::vector<Vec2>& x) const {
    for (const auto& t : faces_)
        if (orientation_2d(at(t[0], x), at(t[1], x), at(t[2], x)) != 1) return false;
    return true;
}

void Scaffold::add_newton_terms(const std::vector<Vec2>& x, const std::vector<Dof>& dof, bool hessian,
                                Eigen::SparseMatrix<double>& K, Eigen::VectorXd& rhs) const {
    Vec2 g[3];
    for (const auto& t : faces_) {
        double phi, d1, d2;
        wall_barrier(0.5 * double_area(at(t[0], x), at(t[1], x), at(t[2], x), g), area_ref_, phi, d1, d2);
        if (d1 == 0 && d2 == 0) continue;
        for (int a = 0; a < 3; ++a) {
            if (t[a] >= nv_) continue;
            const Dof& dv = dof[t[a]];
            const Vec2 ga = 0.5 * g[a];  // the gradient of the area
            for (int i = 0; i < dv.n; ++i) {
                rhs[dv.first + i] -= weight_ * d1 * ga.dot(dv.column(i));
                if (!hessian) continue;
                for (int j = i; j < dv.n; ++j)
                    K.coeffRef(dv.first + i, dv.first + j) += weight_ * d2 * ga.dot(dv.column(i)) * ga.dot(dv.column(j));
            }
        }
    }
}

}  // namespace ctmap

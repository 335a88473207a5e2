#include "ctmap/refine/box_barrier.h"

#include <limits>
#include <utility>

namespace ctmap {

void wall_barrier(double x, double eps, double& phi, double& d1, double& d2) {
    phi = d1 = d2 = 0;
    if (!(x < eps)) return;
    if (!(x > 0)) {
        phi = std::numeric_limits<double>::infinity();
        return;
    }
    const double g = eps / x - 1, g1 = -eps / (x * x), g2 = 2 * eps / (x * x * x);
    phi = g * g;
    d1 = 2 * g * g1;
    d2 = 2 * g1 * g1 + 2 * g * g2;
}

BoxBarrier::BoxBarrier(std::vector<int> vertices, std::vector<double> weight, Vec2 lo, Vec2 hi, double eps)
    : weight_(std::move(weight)), vertices_(std::move(vertices)), lo_(lo), hi_(hi), eps_(eps) {}

double BoxBarrier::value(const std::vector<Vec2>& x) const {
    double b = 0;
    for (int v : vertices_)
        for (int c = 0; c < 2; ++c)
            for (double dist : {x[v][c] - lo_[c], hi_[c] - x[v][c]}) {
                double phi, d1, d2;
                wall_barrier(dist, eps_, phi, d1, d2);
                b += weight_[v] * phi;
            }
    return b;
}

}  // namespace ctmap

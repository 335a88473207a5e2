#pragma once
/// \file box_barrier.h
/// The free border's barrier for the image rectangle (Smith & Schaefer 2015, "Bijective
/// parameterization with free boundaries", §5, for a rectangle's four walls), used by the
/// distortion optimiser (refine/isometric.h, beyond paper §2.4): for a free border vertex v at
/// distance x < eps from a wall, w_v (eps / x - 1)^2; zero beyond eps and infinite at the wall. It
/// keeps the border in the image without stopping the descent the way clamping would.
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// Value, first and second derivative of (eps / x - 1)^2 at the wall distance x: all zero for
/// x >= eps, the value +infinity (derivatives zero) for x <= 0.
void wall_barrier(double x, double eps, double& phi, double& d1, double& d2);

class BoxBarrier {
public:
    /// The barrier holds `vertices` (summed in this order), vertex v with weight `weight[v]`;
    /// `lo`, `hi` the rectangle; `eps` the distance from a wall where it starts.
    /// \pre every listed vertex indexes `weight` and the maps passed below; eps > 0.
    BoxBarrier(std::vector<int> vertices, std::vector<double> weight, Vec2 lo, Vec2 hi, double eps);

    /// The barrier of the map x (the sum over the held vertices in their order, then the walls).
    double value(const std::vector<Vec2>& x) const;

    /// For each held vertex and wall it is near: f(vertex, axis, sign, d1, d2), with sign the
    /// direction of the wall distance along the axis (+1 from the low wall, -1 from the high one)
    /// and d1, d2 the weighted first and second derivative with respect to that distance.
    template <class F>
    void for_terms(const std::vector<Vec2>& x, F&& f) const {
        for (int v : vertices_)
            for (int c = 0; c < 2; ++c)
                for (double sign : {+1.0, -1.0}) {
                    double phi, d1, d2;
                    wall_barrier(sign > 0 ? x[v][c] - lo_[c] : hi_[c] - x[v][c], eps_, phi, d1, d2);
                    if (d1 != 0 || d2 != 0) f(v, c, sign, weight_[v] * d1, weight_[v] * d2);
                }
    }

private:
    std::vector<double> weight_;
    std::vector<int> vertices_;
    Vec2 lo_, hi_;
    double eps_;
};

}  // namespace ctmap

#pragma once
/// \file isometric_problem.h
/// The distortion optimiser's problem (refine/isometric.h, beyond paper §2.4), set up once per
/// call: which vertices move and how (their unknowns, numbered in a fill-reducing order), the
/// faces whose energy can change with their 3D frames scaled to the map's UV area, the image
/// rectangle with the free border's barrier, and the energy.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "ctmap/face_jacobian.h"
#include "ctmap/mesh.h"
#include "ctmap/refine/box_barrier.h"
#include "ctmap/refine/isometric.h"
#include "ctmap/refine/newton_system.h"

namespace ctmap {

struct IsometricProblem {
    int nv = 0;                    ///< the mesh's vertices
    int sigma = 0;                 ///< the map's orientation (+1 counter-clockwise)
    bool local = false;            ///< only IsometricOptions::movable move
    bool parallel = true;
    double scale = 0;              ///< IsometricStats::scale
    double area_sum = 0;           ///< the scaled mesh's area (the energy's divisor)
    double held_energy = 0;        ///< the share of the faces that cannot change (local only)
    std::vector<int> loop;         ///< the border loop
    std::vector<Tri> tris;         ///< the faces whose energy can change, in the unknowns' order
    std::vector<FaceFrame> frame;  ///< their 3D frames, scaled (mirrored for a clockwise map)
    std::vector<Dof> dof;          ///< per vertex
    int unknowns = 0, free_vertices = 0, sliding_vertices = 0;
    Vec2 box_lo, box_hi;           ///< the rectangle the free border stays in (infinite if unbounded)
    std::unique_ptr<BoxBarrier> barrier;
    /// Why there is nothing to optimise ("no free vertex"), or empty.
    std::string nothing;

    /// The energy of the map x with the faces measured against `frames` (frame, or references).
    double energy(const std::vector<FaceFrame>& frames, const std::vector<Vec2>& x) const;
};

/// Sets up the problem of optimise_isometric (its preconditions and errors, which it checks here).
IsometricProblem make_isometric_problem(const TriMesh& mesh, const std::vector<Vec2>& uv,
                                        const std::vector<int>& fixed, const IsometricOptions& options);

/// Sums term(0 .. n-1) in fixed chunks added in order: the same bits whatever the threads.
template <class F>
double chunked_sum(int n, bool parallel, F&& term) {
    constexpr int kChunk = 4096;
    const int chunks = (n + kChunk - 1) / kChunk;
    std::vector<double> part(chunks, 0.0);
    auto run = [&](int c) {
        double s = 0;
        const int end = std::min(n, (c + 1) * kChunk);
        for (int i = c * kChunk; i < end; ++i) s += term(i);
        part[c] = s;
    };
    if (parallel) tbb::parallel_for(0, chunks, run);
    else for (int c = 0; c < chunks; ++c) run(c);
    double s = 0;
    for (double p : part) s += p;
    return s;
}

}  // namespace ctmap

// The distortion optimiser's sparse Cholesky (refine/sparse_cholesky.h): a numeric factorisation
// per new Hessian and a solve per step, on a system with the optimiser's pattern (two unknowns per
// vertex, 2x2 blocks per mesh edge, numbered in fill_reducing_order) and positive definite values.
// CHOLMOD's supernode amalgamation (the default) against the wider one ctmap used until
// 2026-12-06 (16, 64, 192 columns, 99%, 40%, 20% zeros).
#include <benchmark/benchmark.h>

#include "ctmap/io/data_path.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/refine/sparse_cholesky.h"

namespace {

Eigen::SparseMatrix<double> optimiser_like_system(const ctmap::TriMesh& mesh) {
    const int nv = mesh.num_vertices();
    const std::vector<int> order = ctmap::fill_reducing_order(mesh.faces, std::vector<char>(nv, 1));
    std::vector<int> index(nv, -1);
    for (int k = 0; k < int(order.size()); ++k) index[order[k]] = k;
    std::vector<Eigen::Triplet<double>> trip;
    for (const ctmap::Tri& t : mesh.faces)
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b)
                for (int i = 0; i < 2; ++i)
                    for (int j = 0; j < 2; ++j) {
                        const int r = 2 * index[t[a]] + i, c = 2 * index[t[b]] + j;
                        // Diagonally dominant: 6 per face on the diagonal, -1 per face and edge off it.
                        if (r <= c) trip.emplace_back(r, c, a == b ? (i == j ? 6.0 : 0.1) : (i == j ? -1.0 : 0.05));
                    }
    Eigen::SparseMatrix<double> K(2 * nv, 2 * nv);
    K.setFromTriplets(trip.begin(), trip.end());
    K.makeCompressed();
    return K;
}

ctmap::SupernodeAmalgamation amalgamation(bool wide) {
    ctmap::SupernodeAmalgamation a;
    if (wide) a = {{16, 64, 192}, {0.99, 0.4, 0.2}};
    return a;
}

void BM_factorize(benchmark::State& state, const char* name, bool wide) {
    const auto K = optimiser_like_system(ctmap::read_mesh(ctmap::find_data_file(std::string("meshes/") + name)));
    ctmap::SparseCholesky solver(K, false, amalgamation(wide));
    for (auto _ : state)
        if (!solver.factorize(K)) state.SkipWithError("not positive definite");
    state.counters["unknowns"] = double(K.rows());
}

void BM_solve(benchmark::State& state, const char* name, bool wide) {
    const auto K = optimiser_like_system(ctmap::read_mesh(ctmap::find_data_file(std::string("meshes/") + name)));
    ctmap::SparseCholesky solver(K, false, amalgamation(wide));
    if (!solver.factorize(K)) state.SkipWithError("not positive definite");
    const Eigen::VectorXd b = Eigen::VectorXd::Ones(K.rows());
    for (auto _ : state) benchmark::DoNotOptimize(solver.solve(b));
}

}  // namespace

BENCHMARK_CAPTURE(BM_factorize, lion_head_cholmod, "lion-head.off", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_factorize, lion_head_wide, "lion-head.off", true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_factorize, mannequin_devil_cholmod, "mannequin-devil.off", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_factorize, mannequin_devil_wide, "mannequin-devil.off", true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_solve, lion_head_cholmod, "lion-head.off", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_solve, lion_head_wide, "lion-head.off", true)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_solve, mannequin_devil_cholmod, "mannequin-devil.off", false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_solve, mannequin_devil_wide, "mannequin-devil.off", true)->Unit(benchmark::kMillisecond);

// The optimiser's sparse Cholesky factorisation (refine/sparse_cholesky.h): it solves, whole-map
// (CHOLMOD, supernodal) and small (simplicial), and the GOMP_parallel it defines for CHOLMOD's
// OpenMP regions leaves every other caller's parallel regions to libgomp.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>

#include "ctmap/refine/sparse_cholesky.h"

extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned num_threads, unsigned flags);

namespace {

/// The lower triangle of a Newton-like system on an n x n grid with two unknowns per vertex:
/// 2x2 blocks coupling each vertex to its grid neighbours, diagonally dominant.
Eigen::SparseMatrix<double> grid_system(int n) {
    std::vector<Eigen::Triplet<double>> t;
    auto id = [n](int i, int j) { return 2 * (i * n + j); };
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const int a = id(i, j);
            t.emplace_back(a, a, 9.0), t.emplace_back(a + 1, a + 1, 8.0), t.emplace_back(a + 1, a, 0.5);
            if (i + 1 < n) {
                const int b = id(i + 1, j);
                t.emplace_back(b, a, -1.0), t.emplace_back(b + 1, a + 1, -1.0), t.emplace_back(b + 1, a, 0.25);
            }
            if (j + 1 < n) {
                const int b = id(i, j + 1);
                t.emplace_back(b, a, -1.0), t.emplace_back(b + 1, a + 1, -1.0), t.emplace_back(b, a + 1, -0.25);
            }
        }
    Eigen::SparseMatrix<double> K(2 * n * n, 2 * n * n);
    K.setFromTriplets(t.begin(), t.end());
    K.makeCompressed();
    return K;
}

void expect_solves(bool small) {
    const Eigen::SparseMatrix<double> K = grid_system(small ? 20 : 80);
    ctmap::SparseCholesky solver(K, small);
    ASSERT_TRUE(solver.factorize(K));
    Eigen::VectorXd b(K.rows());
    for (int i = 0; i < b.size(); ++i) b[i] = std::sin(0.37 * i) + 0.1 * (i % 7);
    const Eigen::VectorXd x = solver.solve(b);
    const Eigen::VectorXd r = K.selfadjointView<Eigen::Lower>() * x - b;
    EXPECT_LT(r.norm(), 1e-12 * b.norm()) << "relative residual " << r.norm() / b.norm();
    // A second factorisation of new values on the same pattern (the optimiser's use).
    Eigen::SparseMatrix<double> K2 = K;
    for (int c = 0; c < K2.outerSize(); ++c)
        for (Eigen::SparseMatrix<double>::InnerIterator it(K2, c); it; ++it)
            if (it.row() == it.col()) it.valueRef() *= 2;
    ASSERT_TRUE(solver.factorize(K2));
    const Eigen::VectorXd r2 = K2.selfadjointView<Eigen::Lower>() * solver.solve(b) - b;
    EXPECT_LT(r2.norm(), 1e-12 * b.norm());
}

TEST(SparseCholesky, SupernodalSolvesAGridSystem) { expect_solves(false); }

TEST(SparseCholesky, SimplicialSolvesAGridSystem) { expect_solves(true); }

TEST(SparseCholesky, NotPositiveDefiniteIsReported) {
    Eigen::SparseMatrix<double> K = grid_system(60);
    K.coeffRef(10, 10) = -50;
    ctmap::SparseCholesky solver(K, false);
    EXPECT_FALSE(solver.factorize(K));
}

struct TeamLog {
    std::atomic<int> calls{0};
    std::mutex m;
    std::set<int> thread_numbers;
    int (*thread_num)() = nullptr;
};

void log_member(void* data) {
    auto* log = static_cast<TeamLog*>(data);
    ++log->calls;
    const std::lock_guard<std::mutex> lock(log->m);
    log->thread_numbers.insert(log->thread_num());
}

// Outside a SparseCholesky call, a parallel region asked for two threads gets libgomp's team of
// two (were the definition serial for every caller, the body would run once).
TEST(SparseCholesky, OtherOpenMpRegionsGetLibgompsTeam) {
    TeamLog log;
    log.thread_num = reinterpret_cast<int (*)()>(dlsym(RTLD_DEFAULT, "omp_get_thread_num"));
    if (!log.thread_num) GTEST_SKIP() << "libgomp is not loaded (CHOLMOD built without OpenMP)";
    GOMP_parallel(&log_member, &log, 2, 0);
    EXPECT_EQ(log.calls.load(), 2);
    EXPECT_EQ(log.thread_numbers, (std::set<int>{0, 1}));
}

}  // namespace

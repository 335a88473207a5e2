// The optimiser's sparse Cholesky factorisation (refine/sparse_cholesky.h): it solves, whole-map
// (CHOLMOD, supernodal) and small (simplicial), and the GOMP_parallel it defines for CHOLMOD's
// OpenMP regions leaves every other caller's parallel regions to libgomp.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>

#include "ctmap/refine/sparse_cholesky.h"

#include <Eigen/SparseCholesky>

extern "C" void GOMP_parallel(void (*fn)(void*), void* data, unsigned num_threads, unsigned flags);

namespace {

/// The upper triangle of a Newton-like system on an n x n grid with two unknowns per vertex:
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
    Eigen::SparseMatrix<double> lower(2 * n * n, 2 * n * n);
    lower.setFromTriplets(t.begin(), t.end());
    Eigen::SparseMatrix<double> K = lower.transpose();
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
    const Eigen::VectorXd r = K.selfadjointView<Eigen::Upper>() * x - b;
    EXPECT_LT(r.norm(), 1e-12 * b.norm()) << "relative residual " << r.norm() / b.norm();
    // A second factorisation of new values on the same pattern (the optimiser's use).
    Eigen::SparseMatrix<double> K2 = K;
    for (int c = 0; c < K2.outerSize(); ++c)
        for (Eigen::SparseMatrix<double>::InnerIterator it(K2, c); it; ++it)
            if (it.row() == it.col()) it.valueRef() *= 2;
    ASSERT_TRUE(solver.factorize(K2));
    const Eigen::VectorXd r2 = K2.selfadjointView<Eigen::Upper>() * solver.solve(b) - b;
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

/// The 2-unknown system of `faces` with vertex v's unknowns at 2 index[v], 2 index[v] + 1 (upper
/// triangle), and the nonzeros of its Cholesky factor in that order (Eigen's, no reordering).
long factor_nonzeros(const std::vector<ctmap::Tri>& faces, const std::vector<int>& index, int n) {
    std::vector<Eigen::Triplet<double>> t;
    for (const ctmap::Tri& f : faces)
        for (int a : f)
            for (int b : f)
                for (int i = 0; i < 2; ++i)
                    for (int j = 0; j < 2; ++j) {
                        if (index[a] < 0 || index[b] < 0) continue;
                        const int r = 2 * index[a] + i, c = 2 * index[b] + j;
                        if (r <= c) t.emplace_back(r, c, a == b ? (i == j ? 6.0 : 0.1) : (i == j ? -1.0 : 0.05));
                    }
    Eigen::SparseMatrix<double> K(2 * n, 2 * n);
    K.setFromTriplets(t.begin(), t.end());
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Upper, Eigen::NaturalOrdering<int>> llt(K);
    EXPECT_EQ(llt.info(), Eigen::Success);
    return long(llt.matrixL().nestedExpression().nonZeros());
}

// The order lists each vertex with unknowns once and no other, and numbering the system in it
// needs far less fill than the row by row order of a 60 x 60 grid (nested dissection: about
// n log n against the band's n^1.5).
TEST(FillReducingOrder, APermutationOfTheVerticesWithUnknownsThatCutsFill) {
    const int n = 60;
    std::vector<ctmap::Tri> faces;
    for (int i = 0; i + 1 < n; ++i)
        for (int j = 0; j + 1 < n; ++j) {
            const int a = i * n + j;
            faces.push_back({a, a + 1, a + n + 1}), faces.push_back({a, a + n + 1, a + n});
        }
    std::vector<char> has(n * n, 1);
    for (int j = 0; j < n; ++j) has[j] = 0;  // the first row held
    const std::vector<int> order = ctmap::fill_reducing_order(faces, has);
    std::vector<int> index(n * n, -1), rows(n * n, -1);
    ASSERT_EQ(int(order.size()), n * n - n);
    for (int k = 0; k < int(order.size()); ++k) {
        ASSERT_TRUE(order[k] >= 0 && order[k] < n * n && has[order[k]]) << order[k];
        ASSERT_EQ(index[order[k]], -1) << "vertex " << order[k] << " twice";
        index[order[k]] = k;
    }
    for (int v = n; v < n * n; ++v) rows[v] = v - n;
    const long nested = factor_nonzeros(faces, index, n * n - n), banded = factor_nonzeros(faces, rows, n * n - n);
    EXPECT_LT(nested, 0.7 * banded) << nested << " against " << banded;
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

#include "ctmap/refine/sparse_cholesky.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <dlfcn.h>  // dlsym, dlvsym (_GNU_SOURCE, which g++ defines)

#include <algorithm>
#include <mutex>
#include <utility>

#include "ctmap/errors.h"

namespace ctmap {
namespace {

/// CHOLMOD's supernodal factorisation calls BLAS; a threaded OpenBLAS (Debian's
/// libopenblas0-pthread behind libblas.so.3) would make the result depend on its thread count and
/// compete with TBB for the cores. One BLAS thread, if the BLAS is OpenBLAS (looked up at run time:
/// the reference BLAS has no such function).
void single_threaded_blas() {
    using SetThreads = void (*)(int);
    if (auto f = reinterpret_cast<SetThreads>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) f(1);
}

/// Set while this thread is inside a CHOLMOD call made by SparseCholesky (see GOMP_parallel below).
thread_local bool in_cholmod = false;

/// Marks the calling thread as inside CHOLMOD for the guard's lifetime.
class InCholmod {
public:
    InCholmod() : saved_(in_cholmod) { in_cholmod = true; }
    ~InCholmod() { in_cholmod = saved_; }
    InCholmod(const InCholmod&) = delete;
    InCholmod& operator=(const InCholmod&) = delete;

private:
    bool saved_;
};

/// METIS draws from a random number generator whose state is global to the process (GKlib's),
/// seeded at each call: two orderings at once (map_charts maps its charts in parallel) disturbed
/// each other, and the maps then differed in their last bits
/// (Isometric.TwoOptimisersAtOnceGiveTheMapsOfOneAtATime failed 28 of 30 times). One METIS call
/// at a time; the factorisations and solves still run in parallel.
std::mutex metis_lock;

}  // namespace
}  // namespace ctmap

/// Debian's CHOLMOD is built with OpenMP: its supernodal factorisation enters a parallel region
/// (GCC's GOMP_parallel) for each supernode, with an `if` clause that makes most of them a team of
/// one. libgomp ends even such a team with a futex wake: 6,600 system calls per factorisation on
/// mannequin-devil with 50 features (30,430 unknowns), and beside TBB's workers on 2 cores a third
/// of the optimiser's time went to the kernel and libgomp. Setting OpenMP's max-active-levels to 0
/// (which made every region serial) did not remove the wakes. This definition takes the place of
/// libgomp's for the process (CHOLMOD's reference binds to the program's own definition first):
/// on a thread inside a SparseCholesky call the region's body runs once on that thread, which is
/// what a team of one does (CHOLMOD's loops are static, `omp_get_num_threads` is 1 outside a
/// team), so the factor is the same bit for bit. Every other caller, e.g. OpenMP code of a program
/// that links ctmap, is passed on to libgomp's own GOMP_parallel unchanged. A fresh Newton
/// iteration there went from 60 to 36 ms (BENCHMARKS.md, "Speed targets").
extern "C" __attribute__((visibility("default"))) void GOMP_parallel(void (*fn)(void*), void* data, unsigned num_threads,
                                                                    unsigned flags) {
    if (ctmap::in_cholmod) {
        fn(data);
        return;
    }
    using Real = void (*)(void (*)(void*), void*, unsigned, unsigned);
    static const Real real = [] {
        void* f = dlvsym(RTLD_NEXT, "GOMP_parallel", "GOMP_4.0");
        return reinterpret_cast<Real>(f ? f : dlsym(RTLD_NEXT, "GOMP_parallel"));
    }();
    if (real) real(fn, data, num_threads, flags);
    else fn(data);  // no libgomp in the process: nobody else can have asked for a team
}

namespace ctmap {

std::vector<int> fill_reducing_order(const std::vector<Tri>& faces, const std::vector<char>& has_unknowns) {
    const int nv = int(has_unknowns.size());
    std::vector<int> index(nv, -1), vertex;
    for (int v = 0; v < nv; ++v)
        if (has_unknowns[v]) index[v] = int(vertex.size()), vertex.push_back(v);
    const int n = int(vertex.size());
    if (n == 0) return vertex;
    // METIS rather than AMD: on these planar meshes nested dissection needs a third fewer flops
    // per factorisation (mannequin-devil with 50 features: 1.19e8 against 1.77e8), and it costs
    // more only once. The vertex graph: its edges (i, j), i < j, as the upper triangle of a
    // pattern matrix.
    std::vector<std::pair<int, int>> edges;
    edges.reserve(faces.size() * 3);
    for (const Tri& t : faces)
        for (int k = 0; k < 3; ++k) {
            const int a = t[k] < nv ? index[t[k]] : -1, b = t[(k + 1) % 3] < nv ? index[t[(k + 1) % 3]] : -1;
            if (a < 0 || b < 0 || a == b) continue;
            edges.emplace_back(std::min(a, b), std::max(a, b));
        }
    for (auto& e : edges) std::swap(e.first, e.second);  // sort by column, then row
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    cholmod_common c;
    cholmod_start(&c);
    std::vector<int> perm(n);
    bool ok = false;
    {
        const std::lock_guard<std::mutex> one_at_a_time(metis_lock);
        const InCholmod inside;
        if (cholmod_sparse* A = cholmod_allocate_sparse(n, n, edges.size(), true, true, 1, CHOLMOD_PATTERN, &c)) {
            int* p = static_cast<int*>(A->p);
            int* row = static_cast<int*>(A->i);
            std::size_t k = 0;
            for (int col = 0; col < n; ++col) {
                p[col] = int(k);
                while (k < edges.size() && edges[k].first == col) row[k] = edges[k].second, ++k;
            }
            p[n] = int(k);
            ok = cholmod_metis(A, nullptr, 0, true, perm.data(), &c) != 0;
            cholmod_free_sparse(&A, &c);
        }
    }
    cholmod_finish(&c);
    if (!ok) return vertex;  // out of memory in METIS: the vertices' own order (still correct, more fill)
    std::vector<int> order(n);
    for (int k = 0; k < n; ++k) order[k] = vertex[perm[k]];
    return order;
}

struct SparseCholesky::Impl {
    explicit Impl(bool small_) : small(small_) { single_threaded_blas(); }
    bool small;
    Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Upper> supernodal;
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Upper> simplicial;
};

SparseCholesky::SparseCholesky(const Eigen::SparseMatrix<double>& K, bool small, const SupernodeAmalgamation& amalgamation)
    : impl_(nullptr) {
    if (K.rows() != K.cols())
        throw BadInput("", "SparseCholesky: the matrix is " + std::to_string(K.rows()) + " x " +
                               std::to_string(K.cols()) + ", not square");
    impl_ = std::make_unique<Impl>(small);
    if (small) {
        impl_->simplicial.analyzePattern(K);
        return;
    }
    // Supernode amalgamation: CHOLMOD's own by default. Larger supernodes (16, 64, 192 columns,
    // 99%, 40%, 20% zeros) paid while libgomp woke a futex per supernode (GOMP_parallel above);
    // without that, their extra zeros cost more (bench/bench_cholesky.cpp).
    cholmod_common& c = impl_->supernodal.cholmod();
    for (int k = 0; k < 3; ++k) c.nrelax[k] = amalgamation.columns[k], c.zrelax[k] = amalgamation.zeros[k];
    // K comes in a fill-reducing order (fill_reducing_order): factorised as it is, upper
    // triangle, so CHOLMOD reads it in place. (With an ordering of its own it made a permuted
    // transposed copy per factorisation: cholmod_transpose_sym, 6% of the optimiser's time on
    // mannequin-devil with 50 features.)
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_NATURAL;
    c.postorder = false;
    const InCholmod inside;
    impl_->supernodal.analyzePattern(K);
}

SparseCholesky::~SparseCholesky() = default;

bool SparseCholesky::factorize(const Eigen::SparseMatrix<double>& K) {
    if (impl_->small) {
        impl_->simplicial.factorize(K);
        return impl_->simplicial.info() == Eigen::Success;
    }
    const InCholmod inside;
    impl_->supernodal.factorize(K);
    return impl_->supernodal.info() == Eigen::Success;
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& b) const {
    if (impl_->small) return impl_->simplicial.solve(b);
    const InCholmod inside;
    return impl_->supernodal.solve(b);
}

}  // namespace ctmap

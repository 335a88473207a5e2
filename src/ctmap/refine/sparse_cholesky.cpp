#include "ctmap/refine/sparse_cholesky.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <dlfcn.h>  // dlsym, dlvsym (_GNU_SOURCE, which g++ defines)

#include <mutex>

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

struct SparseCholesky::Impl {
    explicit Impl(bool small_) : small(small_) { single_threaded_blas(); }
    bool small;
    Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>, Eigen::Lower> supernodal;
    Eigen::SimplicialLLT<Eigen::SparseMatrix<double>, Eigen::Lower> simplicial;
};

SparseCholesky::SparseCholesky(const Eigen::SparseMatrix<double>& K, bool small) : impl_(nullptr) {
    if (K.rows() != K.cols())
        throw BadInput("", "SparseCholesky: the matrix is " + std::to_string(K.rows()) + " x " +
                               std::to_string(K.cols()) + ", not square");
    impl_ = std::make_unique<Impl>(small);
    if (small) {
        impl_->simplicial.analyzePattern(K);
        return;
    }
    // Relaxed supernode amalgamation: CHOLMOD merges supernodes of up to 16, 64 and 192 columns
    // while under 99%, 40% and 20% of the merged block are zeros (its defaults: 4, 16, 48 columns,
    // 80%, 10%, 5%). Fewer, larger supernodes: each costs an OpenMP region (a futex wake even when
    // serial, see GOMP_parallel above) and a BLAS call, which on these systems cost more than the added
    // fill. A factorisation on mannequin-devil with 50 features (30,430 unknowns) went from 68 to
    // 35 ms, on lion-head with 50 (20,316) from 41 to 24 ms (BENCHMARKS.md, "Speed against CGAL's ARAP").
    cholmod_common& c = impl_->supernodal.cholmod();
    c.nrelax[0] = 16, c.nrelax[1] = 64, c.nrelax[2] = 192;
    c.zrelax[0] = 0.99, c.zrelax[1] = 0.4, c.zrelax[2] = 0.2;
    // The fill-reducing ordering: METIS's nested dissection, which on these planar meshes needs a
    // third fewer flops per factorisation than AMD (mannequin-devil with 50 features: 1.19e8
    // against 1.77e8, 21 against 25 ms per factorisation, the whole optimiser 13% faster) and
    // costs more only once, in the analysis. (CHOLMOD's default tries METIS only when AMD's fill
    // is poor, which on these systems it is not by its measure.)
    c.nmethods = 1;
    c.method[0].ordering = CHOLMOD_METIS;
    // METIS draws from a random number generator whose state is global to the process (GKlib's),
    // seeded at each call: two analyses at once (map_charts maps its charts in parallel) disturbed
    // each other's orderings, and the maps then differed in their last bits
    // (Isometric.TwoOptimisersAtOnceGiveTheMapsOfOneAtATime failed 28 of 30 times). One analysis
    // at a time; the factorisations and solves still run in parallel.
    static std::mutex analysis;
    const std::lock_guard<std::mutex> one_at_a_time(analysis);
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

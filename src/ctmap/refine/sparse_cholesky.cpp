#include "ctmap/refine/sparse_cholesky.h"

#include <Eigen/CholmodSupport>
#include <Eigen/SparseCholesky>
#include <dlfcn.h>

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

/// Debian's CHOLMOD is built with OpenMP and asks for 4 threads (CHOLMOD_OMP_NUM_THREADS) in its
/// supernodal numeric factorisation, whatever the machine. Beside TBB's workers on 2 cores that
/// is oversubscription: on mannequin-devil with 20 features a third of the optimiser's time went
/// to futex waits and wake-ups in libgomp, and the run took 3x as long as with OMP_THREAD_LIMIT=1
/// (bit for bit the same map). While the optimiser runs, OpenMP's max-active-levels is 0, which
/// makes every parallel region run on the calling thread; the caller's setting is put back on
/// exit. (Looked up at run time: libgomp comes with CHOLMOD, not linked by ctmap itself.)
class SerialOpenMp {
public:
    SerialOpenMp() {
        get_ = reinterpret_cast<Get>(dlsym(RTLD_DEFAULT, "omp_get_max_active_levels"));
        set_ = reinterpret_cast<Set>(dlsym(RTLD_DEFAULT, "omp_set_max_active_levels"));
        if (get_ && set_) {
            saved_ = get_();
            set_(0);
        }
    }
    ~SerialOpenMp() {
        if (get_ && set_) set_(saved_);
    }
    SerialOpenMp(const SerialOpenMp&) = delete;
    SerialOpenMp& operator=(const SerialOpenMp&) = delete;

private:
    using Get = int (*)();
    using Set = void (*)(int);
    Get get_ = nullptr;
    Set set_ = nullptr;
    int saved_ = 0;
};

}  // namespace

struct SparseCholesky::Impl {
    explicit Impl(bool small_) : small(small_) { single_threaded_blas(); }
    bool small;
    const SerialOpenMp serial_openmp;
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
    // serial, see SerialOpenMp) and a BLAS call, which on these systems cost more than the added
    // fill. A factorisation on mannequin-devil with 50 features (30,430 unknowns) went from 68 to
    // 35 ms, on lion-head with 50 (20,316) from 41 to 24 ms (BENCHMARKS.md, "Speed against CGAL's ARAP").
    cholmod_common& c = impl_->supernodal.cholmod();
    c.nrelax[0] = 16, c.nrelax[1] = 64, c.nrelax[2] = 192;
    c.zrelax[0] = 0.99, c.zrelax[1] = 0.4, c.zrelax[2] = 0.2;
    impl_->supernodal.analyzePattern(K);
}

SparseCholesky::~SparseCholesky() = default;

bool SparseCholesky::factorize(const Eigen::SparseMatrix<double>& K) {
    if (impl_->small) {
        impl_->simplicial.factorize(K);
        return impl_->simplicial.info() == Eigen::Success;
    }
    impl_->supernodal.factorize(K);
    return impl_->supernodal.info() == Eigen::Success;
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& b) const {
    return impl_->small ? Eigen::VectorXd(impl_->simplicial.solve(b)) : Eigen::VectorXd(impl_->supernodal.solve(b));
}

}  // namespace ctmap

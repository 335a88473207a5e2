#pragma once
/// \file sparse_cholesky.h
/// The distortion optimiser's sparse Cholesky factorisation (refine/isometric.h, beyond paper
/// §2.4): the symbolic analysis once, then a numeric factorisation per new Hessian and a solve per
/// step. Whole maps: SuiteSparse's CHOLMOD, supernodal, with relaxed amalgamation; small local
/// systems (`ctmap serve`'s moves): Eigen's simplicial LLT with AMD ordering.
#include <Eigen/SparseCore>

#include <memory>

namespace ctmap {

class SparseCholesky {
public:
    /// Analyses the pattern of K (its lower triangle is read; compressed). `small`: the simplicial
    /// factorisation, faster than CHOLMOD's supernodal one on systems of a few thousand unknowns
    /// (its OpenMP team costs more than the work there). BLAS (OpenBLAS) is set to one thread, and
    /// CHOLMOD's OpenMP regions run on the calling thread without libgomp's team (see the source:
    /// CHOLMOD's threads beside TBB's workers tripled the optimiser's time, and libgomp's team of
    /// one still cost a system call per supernode); OpenMP elsewhere in the process is untouched.
    /// \pre K is square.
    SparseCholesky(const Eigen::SparseMatrix<double>& K, bool small);
    ~SparseCholesky();
    SparseCholesky(const SparseCholesky&) = delete;
    SparseCholesky& operator=(const SparseCholesky&) = delete;

    /// Factorises K, whose pattern is the one analysed. False when K is not positive definite
    /// (numerically).
    bool factorize(const Eigen::SparseMatrix<double>& K);
    /// K^-1 b with the last factorisation. \pre factorize returned true.
    Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace ctmap

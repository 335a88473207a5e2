#pragma once
/// \file sparse_cholesky.h
/// The distortion optimiser's sparse Cholesky factorisation (refine/isometric.h, beyond paper
/// §2.4): the symbolic analysis once, then a numeric factorisation per new Hessian and a solve per
/// step. Whole maps: SuiteSparse's CHOLMOD, supernodal, on a system numbered in
/// fill_reducing_order; small local systems (`ctmap serve`'s moves): Eigen's simplicial LLT with
/// AMD ordering.
#include <Eigen/SparseCore>

#include <memory>
#include <vector>

#include "ctmap/mesh.h"

namespace ctmap {

/// A fill-reducing order of the vertices v of `faces` with `has_unknowns[v]`: METIS's nested
/// dissection of the mesh's vertex graph (through CHOLMOD), postordered. Numbering a system's
/// unknowns vertex by vertex in this order lets SparseCholesky factorise it as it is given, with no
/// permuted copy per factorisation. Returns those vertices, first to last.
/// \pre has_unknowns has an entry per vertex of `faces`.
std::vector<int> fill_reducing_order(const std::vector<Tri>& faces, const std::vector<char>& has_unknowns);

/// How CHOLMOD merges the columns of the supernodal factor: supernodes of up to `columns[k]`
/// columns while under `zeros[k]` of the merged block are zeros (its nrelax, zrelax). The defaults
/// are CHOLMOD's own (bench/bench_cholesky.cpp compares them with wider ones).
struct SupernodeAmalgamation {
    std::size_t columns[3] = {4, 16, 48};
    double zeros[3] = {0.8, 0.1, 0.05};
};

class SparseCholesky {
public:
    /// Analyses the pattern of K (its upper triangle is read; compressed). Whole maps (not `small`)
    /// are factorised in K's own order: number the unknowns in fill_reducing_order. `small`: the
    /// simplicial factorisation with AMD's ordering, faster than CHOLMOD's supernodal one on
    /// systems of a few thousand unknowns. `amalgamation`: CHOLMOD's supernodes. BLAS (OpenBLAS) is set to one thread, and
    /// CHOLMOD's OpenMP regions run on the calling thread without libgomp's team (see the source:
    /// CHOLMOD's threads beside TBB's workers tripled the optimiser's time, and libgomp's team of
    /// one still cost a system call per supernode); OpenMP elsewhere in the process is untouched.
    /// \pre K is square.
    SparseCholesky(const Eigen::SparseMatrix<double>& K, bool small, const SupernodeAmalgamation& amalgamation = {});
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

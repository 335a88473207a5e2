#pragma once
/// \file mean_value_embedding.h
/// Embedding of the patches of a cut mesh into their image triangles (paper §2.4): the three
/// sides of a patch on the triangle's sides by arc length, the corners exactly on the features'
/// image points, the interior by Floater's mean value coordinates (convex combination map).
#include <vector>

#include "ctmap/cut/cut_mesh.h"
#include "ctmap/mesh.h"

namespace ctmap {

/// Floater's mean value weights of `center` with respect to its closed ring of neighbours
/// `ring` (in cyclic order; the last neighbour is followed by the first), computed from the 3D
/// angles at `center`: w_j = (tan(a_{j-1}/2) + tan(a_j/2)) / |ring_j - center|, a_j the angle
/// between ring_j and ring_{j+1}. Every weight is positive; the result is normalized to sum 1.
/// For a planar star-shaped ring the weights reproduce linear functions:
/// sum_j w_j ring_j = center (Floater 2003, paper ref. [5]).
/// \pre ring.size() >= 2; no ring point equals `center`; no angle a_j equals pi.
/// \throw std::invalid_argument if a precondition fails (a weight would be zero, infinite or NaN).
std::vector<double> mean_value_weights(const Vec3& center, const std::vector<Vec3>& ring);

/// tan(a/2) for the angle a between u and v, in the form |u x v| / (|u||v| + u.v) that stays
/// accurate for small angles (the usual (1 - cos a) / sin a loses every digit there).
double half_angle_tangent(const Vec3& u, const Vec3& v);

/// Counts of `split_flat_edges`.
struct FlatEdgeStats {
    int edges_split = 0;     ///< flat edges found and split (= vertices added)
};

/// Splits every "flat" edge of `cut` at its midpoint: a non-side edge whose two ends lie on the
/// same side of its patch (corners count as lying on both their sides). Its UV triangle would
/// otherwise be flat, since both ends land on one straight side of the image triangle (DESIGN §2
/// condition 5; Floater's theorem needs no such "dividing edge" on one side). Each of the edge's
/// two faces (in the same patch: sides separate patches) is split in two; the new vertex is
/// appended (vertex order kept, DESIGN §3), lies on the input surface (the edge lies in one input
/// face), and gets its `vertex_face` / `vertex_bary` in `input`. face_patch and sides stay valid.
/// \pre `cut` is a well-formed cut of `input` (sides are vertex chains on the patch borders,
///      vertex_face indexes `input.faces`, or vertex_face is empty and is then left empty).
/// \throw InternalError if a flat edge does not have two faces of one patch (a malformed cut).
FlatEdgeStats split_flat_edges(CutMesh& cut, const TriMesh& input);

/// Number of flat edges (see `split_flat_edges`) in `cut`; 0 is what `embed_patches` needs.
int count_flat_edges(const CutMesh& cut);

/// Options of `embed_patches`.
struct EmbedOptions {
    enum class Solver { sparse_lu, bicgstab };
    /// SparseLU is exact up to rounding and fast for patches of up to ~1e5 vertices; BiCGSTAB
    /// (diagonal preconditioner) uses less memory on very large patches.
    Solver solver = Solver::sparse_lu;
    double bicgstab_tolerance = 1e-13;  ///< relative residual of the iterative solver
    bool parallel = true;               ///< solve the patches in parallel (TBB); they are independent
};

/// Maps every patch of `cut` into its image triangle (paper §2.4): the corner vertices get
/// exactly `feature_uv` of their features (bitwise), the vertices of each side are spread along
/// the triangle's side in proportion to their 3D arc length (computed once per triangulation
/// edge, so the two patches that share a side agree bitwise), and the interior vertices solve
/// the mean value system u_v = sum_j w_vj u_j (Floater's convex combination map: a bijection
/// onto the triangle when there is no flat edge). Patches are solved in parallel with one sparse
/// factorization each.
/// \return one UV per vertex of `cut.mesh` (vertices in no patch face get NaN).
/// \pre feature_uv has one entry per feature; each patch's image triangle is non-degenerate;
///      `count_flat_edges(cut) == 0` (call `split_flat_edges` first).
/// \throw InternalError for a malformed cut (sides not joining the corners, a flat edge, an
///        interior vertex with a face outside its patch); SolverError if a factorization fails.
std::vector<Vec2> embed_patches(const CutMesh& cut, const std::vector<Vec2>& feature_uv,
                                const EmbedOptions& options = {});

}  // namespace ctmap

#include "ctmap/embed/mean_value_embedding.h"

#include <tbb/parallel_for.h>

#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>

#include "ctmap/edge_key.h"
#include "ctmap/errors.h"

namespace ctmap {
namespace {

/// Where the sides of the patches run: per vertex, the (patch, side bit mask) pairs (a vertex
/// lies on the sides of a handful of patches at most), and the set of side edges.
struct SideIndex {
    std::vector<std::vector<std::pair<int, int>>> masks;
    std::unordered_set<std::uint64_t> side_edges;

    explicit SideIndex(const CutMesh& cut) : masks(cut.mesh.num_vertices()) {
        const int nv = cut.mesh.num_vertices();
        for (int p = 0; p < int(cut.patches.size()); ++p)
            for (int k = 0; k < 3; ++k) {
                const std::vector<int>& s = cut.patches[p].sides[k];
                for (std::size_t i = 0; i < s.size(); ++i) {
                    const int v = s[i];
                    if (v < 0 || v >= nv)
                        throw InternalError("embed: side " + std::to_string(k) + " of patch " + std::to_string(p) +
                                            " names vertex " + std::to_string(v) + ", which does not exist");
                    add(v, p, 1 << k);
                    if (i + 1 < s.size()) side_edges.insert(edge_key(v, s[i + 1]));
                }
            }
    }
    void add(int v, int p, int bit) {
        for (auto& [q, m] : masks[v])
            if (q == p) {
                m |= bit;
                return;
            }
        masks[v].push_back({p, bit});
    }
    int mask(int v, int p) const {
        for (const auto& [q, m] : masks[v])
            if (q == p) return m;
        return 0;
    }
    bool on_any_side(int v) const { return !masks[v].empty(); }
};

/// The flat edges of `cut` (see split_flat_edges), each once, as (a, b) with a < b.
std::vector<std::pair<int, int>> find_flat_edges(const CutMesh& cut, const SideIndex& sides) {
    std::vector<std::pair<int, int>> out;
    std::unordered_set<std::uint64_t> seen;
    const auto& faces = cut.mesh.faces;
    for (int f = 0; f < int(faces.size()); ++f) {
        const int p = cut.face_patch[f];
        for (int k = 0; k < 3; ++k) {
            const int a = faces[f][k], b = faces[f][(k + 1) % 3];
            if ((sides.mask(a, p) & sides.mask(b, p)) == 0) continue;
            const std::uint64_t key = edge_key(a, b);
            if (sides.side_edges.count(key) || !seen.insert(key).second) continue;
            out.push_back({std::min(a, b), std::max(a, b)});
        }
    }
    return out;
}

void check_face_patch(const CutMesh& cut) {
    if (cut.face_patch.size() != cut.mesh.faces.size())
        throw InternalError("embed: the cut has " + std::to_string(cut.face_patch.size()) + " patch ids for " +
                            std::to_string(cut.mesh.faces.size()) + " faces");
    for (int p : cut.face_patch)
        if (p < 0 || p >= int(cut.patches.size()))
            throw InternalError("embed: a face names patch " + std::to_string(p) + ", which does not exist");
}

/// Barycentric coordinates of P in the plane of triangle (A, B, C), and P's distance to it.
Vec3 barycentric(const Vec3& P, const Vec3& A, const Vec3& B, const Vec3& C, double* plane_distance) {
    const Vec3 n = (B - A).cross(C - A);
    const double nn = n.squaredNorm();
    if (!(nn > 0)) {
        *plane_distance = std::numeric_limits<double>::infinity();
        return Vec3::Constant(-1);
    }
    const double l1 = (P - A).cross(C - A).dot(n) / nn;
    const double l2 = (B - A).cross(P - A).dot(n) / nn;
    *plane_distance = std::abs((P - A).dot(n)) / std::sqrt(nn);
    return Vec3(1 - l1 - l2, l1, l2);
}

}  // namespace

double half_angle_tangent(const Vec3& u, const Vec3& v) {
    const double cross = u.cross(v).norm();
    const double denom = u.norm() * v.norm() + u.dot(v);
    return cross / denom;
}

std::vector<double> mean_value_weights(const Vec3& center, const std::vector<Vec3>& ring) {
    const std::size_t n = ring.size();
    if (n < 2) throw std::invalid_argument("mean_value_weights: a ring needs at least 2 neighbours");
    std::vector<double> tan_half(n), w(n, 0.0);
    for (std::size_t j = 0; j < n; ++j) tan_half[j] = half_angle_tangent(ring[j] - center, ring[(j + 1) % n] - center);
    double sum = 0;
    for (std::size_t j = 0; j < n; ++j) {
        const double r = (ring[j] - center).norm();
        w[j] = (tan_half[(j + n - 1) % n] + tan_half[j]) / r;
        if (!(w[j] > 0) || !std::isfinite(w[j]))
            throw std::invalid_argument("mean_value_weights: neighbour " + std::to_string(j) +
                                        " gives a weight that is not positive and finite (coincident point or a "
                                        "straight angle)");
        sum += w[j];
    }
    for (double& x : w) x /= sum;
    return w;
}

int count_flat_edges(const CutMesh& cut) {
    check_face_patch(cut);
    const SideIndex sides(cut);
    return int(find_flat_edges(cut, sides).size());
}

FlatEdgeStats split_flat_edges(CutMesh& cut, const TriMesh& input) {
    check_face_patch(cut);
    FlatEdgeStats stats;
    TriMesh& m = cut.mesh;
    const bool keep_bary = cut.vertex_face.size() == m.positions.size() && !m.positions.empty();
    // Splitting an edge creates edges to its (interior) midpoint only, so one pass removes every
    // flat edge (embed_patches checks that none is left).
    const std::vector<std::pair<int, int>> flat = find_flat_edges(cut, SideIndex(cut));
    if (flat.empty()) return stats;
    // Faces around the ends of flat edges only (the only lists looked up below), in the cut
    // mesh and in the input: lists for every vertex of a million-triangle mesh cost more than
    // all the splitting.
    std::unordered_map<int, std::vector<int>> vf, input_vertex_faces;
    for (const auto& [a, b] : flat) vf[a], vf[b];
    for (int f = 0; f < m.num_faces(); ++f)
        for (int v : m.faces[f])
            if (auto it = vf.find(v); it != vf.end()) it->second.push_back(f);
    if (keep_bary) {
        for (const auto& [a, b] : flat)
            for (int v : {a, b})
                if (v < cut.num_input_vertices && v < input.num_vertices()) input_vertex_faces[v];
        for (int f = 0; f < input.num_faces(); ++f)
            for (int v : input.faces[f])
                if (auto it = input_vertex_faces.find(v); it != input_vertex_faces.end()) it->second.push_back(f);
    }
    auto update = [&](int v, int f_old, int f_new) {
        auto it = vf.find(v);
        if (it == vf.end()) return;
        if (f_old >= 0) it->second.erase(std::find(it->second.begin(), it->second.end(), f_old));
        it->second.push_back(f_new);
    };
    for (const auto& [a, b] : flat) {
        std::vector<int> faces;
        for (int f : vf.at(a))
            if (std::find(m.faces[f].begin(), m.faces[f].end(), b) != m.faces[f].end()) faces.push_back(f);
        if (faces.size() != 2 || cut.face_patch[faces[0]] != cut.face_patch[faces[1]])
            throw InternalError("embed: edge (" + std::to_string(a) + ", " + std::to_string(b) +
                                ") joins two vertices of one side but does not have two faces of one patch");
        const int mid = m.num_vertices();
        m.positions.push_back(0.5 * (m.positions[a] + m.positions[b]));
        for (int f : faces) {
            Tri& t = m.faces[f];
            int k = 0;
            while (!((t[k] == a || t[k] == b) && (t[(k + 1) % 3] == a || t[(k + 1) % 3] == b))) ++k;
            const int x = t[k], y = t[(k + 1) % 3], z = t[(k + 2) % 3];
            t = Tri{x, mid, z};
            const int g = m.num_faces();
            m.faces.push_back(Tri{mid, y, z});
            cut.face_patch.push_back(cut.face_patch[f]);
            update(y, f, g);
            update(z, -1, g);
        }
        if (keep_bary) {
            // The edge lies in one input face (the cut only splits); find it among the faces
            // of its ends and express the midpoint there.
            std::vector<int> candidates{cut.vertex_face[a], cut.vertex_face[b]};
            for (int v : {a, b})
                if (auto it = input_vertex_faces.find(v); it != input_vertex_faces.end())
                    candidates.insert(candidates.end(), it->second.begin(), it->second.end());
            int best = -1;
            double best_score = -std::numeric_limits<double>::infinity();
            Vec3 best_bary = Vec3::Zero();
            const Vec3& P = m.positions[mid];
            for (int f : candidates) {
                if (f < 0 || f >= input.num_faces()) continue;
                const Tri& t = input.faces[f];
                double dist = 0;
                const Vec3 l = barycentric(P, input.positions[t[0]], input.positions[t[1]], input.positions[t[2]],
                                           &dist);
                const double scale = (input.positions[t[1]] - input.positions[t[0]]).norm() +
                                     (input.positions[t[2]] - input.positions[t[0]]).norm();
                const double score = l.minCoeff() - dist / std::max(scale, 1e-300);
                if (score > best_score) {
                    best_score = score;
                    best = f;
                    best_bary = l;
                }
            }
            if (best < 0)
                throw InternalError("embed: the midpoint of edge (" + std::to_string(a) + ", " + std::to_string(b) +
                                    ") lies in none of its ends' input faces");
            cut.vertex_face.push_back(best);
            cut.vertex_bary.push_back(best_bary);
        }
        ++stats.edges_split;
    }
    return stats;
}

std::vector<Vec2> embed_patches(const CutMesh& cut, const std::vector<Vec2>& feature_uv, const EmbedOptions& options) {
    check_face_patch(cut);
    const TriMesh& m = cut.mesh;
    const int nv = m.num_vertices(), np = int(cut.patches.size());
    if (feature_uv.size() != cut.feature_vertex.size())
        throw InternalError("embed: " + std::to_string(feature_uv.size()) + " feature UVs for " +
                            std::to_string(cut.feature_vertex.size()) + " features");
    const SideIndex sides(cut);
    if (const auto flat = find_flat_edges(cut, sides); !flat.empty())
        throw InternalError("embed: " + std::to_string(flat.size()) + " flat edge(s), e.g. (" +
                            std::to_string(flat[0].first) + ", " + std::to_string(flat[0].second) +
                            "): call split_flat_edges before embed_patches");

    std::vector<Vec2> uv(nv, Vec2::Constant(std::numeric_limits<double>::quiet_NaN()));

    // Corners first, bitwise: the written UV of a feature is its constraint (DESIGN §3).
    for (int p = 0; p < np; ++p) {
        const Patch& P = cut.patches[p];
        for (int k = 0; k < 3; ++k) {
            const int f = P.corners[k], g = P.corners[(k + 1) % 3];
            if (f < 0 || f >= int(feature_uv.size()) || g < 0 || g >= int(feature_uv.size()))
                throw InternalError("embed: patch " + std::to_string(p) + " names a feature that does not exist");
            const std::vector<int>& s = P.sides[k];
            if (s.size() < 2 || s.front() != cut.feature_vertex[f] || s.back() != cut.feature_vertex[g])
                throw InternalError("embed: side " + std::to_string(k) + " of patch " + std::to_string(p) +
                                    " does not run from the vertex of feature " + std::to_string(f) +
                                    " to that of feature " + std::to_string(g));
        }
        const Vec2 e1 = feature_uv[P.corners[1]] - feature_uv[P.corners[0]];
        const Vec2 e2 = feature_uv[P.corners[2]] - feature_uv[P.corners[0]];
        if (!(std::abs(e1.x() * e2.y() - e1.y() * e2.x()) > 0))
            throw InternalError("embed: the image triangle of patch " + std::to_string(p) + " is degenerate");
    }
    for (std::size_t f = 0; f < cut.feature_vertex.size(); ++f) uv[cut.feature_vertex[f]] = feature_uv[f];

    // Sides: once per triangulation edge, always walked from its lower feature to its higher
    // one, so both patches that share it see bitwise the same UVs whatever the order.
    std::map<std::pair<int, int>, const std::vector<int>*> done;
    for (int p = 0; p < np; ++p) {
        const Patch& P = cut.patches[p];
        for (int k = 0; k < 3; ++k) {
            int f = P.corners[k], g = P.corners[(k + 1) % 3];
            const std::vector<int>& s = P.sides[k];
            const auto key = std::make_pair(std::min(f, g), std::max(f, g));
            if (auto it = done.find(key); it != done.end()) {
                const std::vector<int>& o = *it->second;
                if (o.size() != s.size() || !std::equal(o.begin(), o.end(), s.rbegin()))
                    throw InternalError("embed: the two patches beside features " + std::to_string(key.first) + " and " +
                                        std::to_string(key.second) + " disagree on the path between them");
                continue;
            }
            done[key] = &s;
            std::vector<int> chain(s);
            if (f > g) {
                std::reverse(chain.begin(), chain.end());
                std::swap(f, g);
            }
            std::vector<double> arc(chain.size(), 0.0);
            for (std::size_t i = 1; i < chain.size(); ++i)
                arc[i] = arc[i - 1] + (m.positions[chain[i]] - m.positions[chain[i - 1]]).norm();
            const double length = arc.back();
            if (!(length > 0))
                throw InternalError("embed: the path between features " + std::to_string(f) + " and " +
                                    std::to_string(g) + " has zero length");
            const Vec2 A = feature_uv[f], B = feature_uv[g];
            for (std::size_t i = 1; i + 1 < chain.size(); ++i) uv[chain[i]] = A + (arc[i] / length) * (B - A);
        }
    }

    // Interior vertices of each patch: not on any side. Each belongs to exactly one patch.
    std::vector<int> owner(nv, -1), local(nv, -1);
    std::vector<std::vector<int>> patch_faces(np), patch_interior(np);
    for (int f = 0; f < m.num_faces(); ++f) {
        const int p = cut.face_patch[f];
        patch_faces[p].push_back(f);
        for (int v : m.faces[f]) {
            if (sides.on_any_side(v)) continue;
            if (owner[v] < 0) {
                owner[v] = p;
                local[v] = int(patch_interior[p].size());
                patch_interior[p].push_back(v);
            } else if (owner[v] != p) {
                throw InternalError("embed: vertex " + std::to_string(v) + " lies inside patches " +
                                    std::to_string(owner[v]) + " and " + std::to_string(p) +
                                    " but on no side between them");
            }
        }
    }

    auto solve_patch = [&](int p) {
        const std::vector<int>& inner = patch_interior[p];
        const int n = int(inner.size());
        if (n == 0) return;
        // Mean value weights accumulated face by face: the face (v, a, b) with angle alpha at v
        // adds tan(alpha/2)/|a-v| to w_va and tan(alpha/2)/|b-v| to w_vb (Floater 2003), so no
        // cyclic ordering of the one-ring is needed.
        struct Entry {
            int row;
            int col;  // vertex id
            double w;
        };
        std::vector<Entry> entries;
        entries.reserve(patch_faces[p].size() * 6);
        std::vector<double> total(n, 0.0);
        for (int f : patch_faces[p]) {
            const Tri& t = m.faces[f];
            for (int k = 0; k < 3; ++k) {
                const int v = t[k];
                if (owner[v] != p) continue;
                const int a = t[(k + 1) % 3], b = t[(k + 2) % 3];
                const Vec3 da = m.positions[a] - m.positions[v], db = m.positions[b] - m.positions[v];
                const double th = half_angle_tangent(da, db);
                const double wa = th / da.norm(), wb = th / db.norm();
                if (!(wa > 0) || !(wb > 0) || !std::isfinite(wa) || !std::isfinite(wb))
                    throw InternalError("embed: face " + std::to_string(f) + " is degenerate in 3D at vertex " +
                                        std::to_string(v) + " (no positive mean value weight)");
                entries.push_back({local[v], a, wa});
                entries.push_back({local[v], b, wb});
                total[local[v]] += wa + wb;
            }
        }
        // Rows normalized to sum 1 (u_v - sum w_vj u_j = 0): the scale of the mesh then does
        // not matter to the solver.
        std::vector<Eigen::Triplet<double>> trip;
        trip.reserve(entries.size() + n);
        Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(n, 2);
        for (int i = 0; i < n; ++i) trip.emplace_back(i, i, 1.0);
        for (const Entry& e : entries) {
            const double w = e.w / total[e.row];
            if (owner[e.col] == p) trip.emplace_back(e.row, local[e.col], -w);
            else rhs.row(e.row) += w * uv[e.col].transpose();
        }
        Eigen::SparseMatrix<double> A(n, n);
        A.setFromTriplets(trip.begin(), trip.end());
        Eigen::MatrixX2d x(n, 2);
        if (options.solver == EmbedOptions::Solver::sparse_lu) {
            Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
            lu.analyzePattern(A);
            lu.factorize(A);
            if (lu.info() != Eigen::Success)
                throw SolverError("embed: the mean value system of patch " + std::to_string(p) +
                                  " could not be factorized (" + lu.lastErrorMessage() + ")");
            x = lu.solve(rhs);
        } else {
            Eigen::BiCGSTAB<Eigen::SparseMatrix<double>, Eigen::DiagonalPreconditioner<double>> it;
            it.setTolerance(options.bicgstab_tolerance);
            it.setMaxIterations(std::max(1000, 20 * n));
            it.compute(A);
            for (int c = 0; c < 2; ++c) {
                x.col(c) = it.solve(rhs.col(c));
                if (it.info() != Eigen::Success)
                    throw SolverError("embed: BiCGSTAB did not converge on patch " + std::to_string(p) + " (error " +
                                      std::to_string(it.error()) + " after " + std::to_string(it.iterations()) +
                                      " iterations)");
            }
        }
        if (!x.allFinite())
            throw SolverError("embed: the mean value system of patch " + std::to_string(p) + " gave a non-finite UV");
        for (int i = 0; i < n; ++i) uv[inner[i]] = x.row(i).transpose();
    };
    if (options.parallel) {
        tbb::parallel_for(0, np, [&](int p) { solve_patch(p); });
    } else {
        for (int p = 0; p < np; ++p) solve_patch(p);
    }
    return uv;
}

}  // namespace ctmap

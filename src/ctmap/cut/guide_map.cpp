#include "ctmap/cut/guide_map.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <unordered_map>

#include "ctmap/errors.h"

namespace ctmap {

std::vector<Vec2> guide_map(const TriMesh& mesh, const std::vector<int>& feature_vertex, const FeatureTriangulation& ft) {
    const WorkMesh wm(mesh);
    const int n = mesh.num_vertices();
    std::vector<Vec2> uv(n, Vec2::Zero());
    std::vector<char> fixed(n, 0);
    std::unordered_map<int, int> feature_of;
    for (int i = 0; i < int(feature_vertex.size()); ++i) feature_of[feature_vertex[i]] = i;
    for (int i = 0; i < int(feature_vertex.size()); ++i) {
        uv[feature_vertex[i]] = ft.points[i];
        fixed[feature_vertex[i]] = 1;
    }
    // The border: each arc between consecutive border features onto the straight side between
    // their image points, by arc length.
    std::vector<int> loop = wm.border_loop();
    const auto first = std::find_if(loop.begin(), loop.end(), [&](int v) { return feature_of.count(v) > 0; });
    if (first == loop.end()) throw BadInput("", "guide_map: no feature on the border");
    std::rotate(loop.begin(), first, loop.end());
    loop.push_back(loop.front());
    std::size_t start = 0;
    for (std::size_t i = 1; i < loop.size(); ++i) {
        if (!feature_of.count(loop[i])) continue;
        double total = 0;
        std::vector<double> acc{0};
        for (std::size_t j = start; j < i; ++j)
            acc.push_back(total += (mesh.positions[loop[j + 1]] - mesh.positions[loop[j]]).norm());
        const Vec2 a = uv[loop[start]], b = uv[loop[i]];
        for (std::size_t j = start + 1; j < i; ++j) {
            const double t = total > 0 ? acc[j - start] / total : double(j - start) / double(i - start);
            uv[loop[j]] = a + t * (b - a);
            fixed[loop[j]] = 1;
        }
        start = i;
    }
    // Biharmonic interpolation (the square of the graph Laplacian): smooth through the pinned
    // features. A harmonic one would be flat around each pin with a spike at it (point
    // constraints of a harmonic function), folding a quarter of the faces under a moderate twist.
    std::vector<Eigen::Triplet<double>> trip;
    for (std::size_t e = 0; e < wm.edges.size(); ++e) {
        const int a = key_lo(wm.edges[e]), b = key_hi(wm.edges[e]);
        trip.emplace_back(a, b, -1.0);
        trip.emplace_back(b, a, -1.0);
        trip.emplace_back(a, a, 1.0);
        trip.emplace_back(b, b, 1.0);
    }
    Eigen::SparseMatrix<double> L(n, n);
    L.setFromTriplets(trip.begin(), trip.end());
    const Eigen::SparseMatrix<double> Q = L * L;
    std::vector<int> index(n, -1);
    int m = 0;
    for (int v = 0; v < n; ++v)
        if (!fixed[v]) index[v] = m++;
    if (m == 0) return uv;
    std::vector<Eigen::Triplet<double>> qt;
    Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(m, 2);
    for (int k = 0; k < Q.outerSize(); ++k)
        for (Eigen::SparseMatrix<double>::InnerIterator it(Q, k); it; ++it) {
            const int r = int(it.row()), c = int(it.col());
            if (fixed[r]) continue;
            if (fixed[c]) rhs.row(index[r]) -= it.value() * uv[c].transpose();
            else qt.emplace_back(index[r], index[c], it.value());
        }
    Eigen::SparseMatrix<double> A(m, m);
    A.setFromTriplets(qt.begin(), qt.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
    if (solver.info() != Eigen::Success) throw SolverError("guide_map: the bi-Laplacian could not be factorized");
    const Eigen::MatrixX2d x = solver.solve(rhs);
    for (int v = 0; v < n; ++v)
        if (!fixed[v]) uv[v] = x.row(index[v]).transpose();
    return uv;
}

void extend_guide(const WorkMesh& mesh, std::vector<Vec2>& guide) {
    for (int v = int(guide.size()); v < mesh.num_vertices(); ++v) {
        if (mesh.vertex_faces[v].empty()) {
            guide.push_back(Vec2::Zero());
            continue;
        }
        const Tri& t = mesh.input_faces[mesh.origin[mesh.vertex_faces[v][0]]];
        const Vec3 &A = mesh.positions[t[0]], &B = mesh.positions[t[1]], &C = mesh.positions[t[2]];
        const Vec3 nrm = (B - A).cross(C - A);
        if (!(nrm.squaredNorm() > 0)) {  // a degenerate input face: its corners' mean
            guide.push_back((guide[t[0]] + guide[t[1]] + guide[t[2]]) / 3);
            continue;
        }
        const Vec3& P = mesh.positions[v];
        const double l1 = (P - A).cross(C - A).dot(nrm) / nrm.squaredNorm();
        const double l2 = (B - A).cross(P - A).dot(nrm) / nrm.squaredNorm();
        guide.push_back((1 - l1 - l2) * guide[t[0]] + l1 * guide[t[1]] + l2 * guide[t[2]]);
    }
}

}  // namespace ctmap

#include "ctmap/refine/newton_system.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace ctmap {

NewtonSystem::NewtonSystem(const std::vector<Tri>& faces, const std::vector<Dof>& dof, int unknowns)
    : K_(unknowns, unknowns), diag_(unknowns, -1) {
    const int nv = int(dof.size()), nf = int(faces.size());
    // The corners of each vertex with unknowns, faces ascending (a counting sort).
    std::vector<int> owner_of(nv, -1);
    // In the unknowns' order: a column's neighbours in the loop are its neighbours in memory.
    std::vector<int> owners;  // the vertices with unknowns
    for (int v = 0; v < nv; ++v)
        if (dof[v].n > 0) owners.push_back(v);
    std::sort(owners.begin(), owners.end(), [&](int a, int b) { return dof[a].first < dof[b].first; });
    for (int o = 0; o < int(owners.size()); ++o) owner_of[owners[o]] = o, owner_dof_.push_back(dof[owners[o]]);
    const int no = int(owners.size());
    corner_start_.assign(no + 1, 0);
    for (const Tri& t : faces)
        for (int v : t)
            if (owner_of[v] >= 0) ++corner_start_[owner_of[v] + 1];
    for (int o = 0; o < no; ++o) corner_start_[o + 1] += corner_start_[o];
    corner_.resize(corner_start_[no]);
    {
        std::vector<int> fill(corner_start_.begin(), corner_start_.end() - 1);
        for (int f = 0; f < nf; ++f)
            for (int k = 0; k < 3; ++k)
                if (owner_of[faces[f][k]] >= 0) corner_[fill[owner_of[faces[f][k]]]++] = 3 * f + k;
    }
    // The pattern, column by column: the upper triangle, (r, c) with r <= c. Owner v's first
    // column holds the first unknowns of its neighbours w (and v) numbered up to v's, each
    // followed by w's second; its second column the same rows and its own second unknown. The
    // rank of a block (w, v) is where w's first row sits in v's columns (the same in both).
    std::vector<int> column_of(unknowns, -1);  // owner of each unknown's column
    for (int o = 0; o < no; ++o)
        for (int j = 0; j < owner_dof_[o].n; ++j) column_of[owner_dof_[o].first + j] = o;
    std::vector<int> outer(unknowns + 1, 0), inner, firsts;
    rank_.assign(corner_.size() * 3, -1);
    neighbour_.assign(corner_.size() * 3, -1);
    for (int c = 0; c < unknowns; ++c) {
        outer[c] = int(inner.size());
        const int o = column_of[c];
        const Dof& dv = owner_dof_[o];
        const int j = c - dv.first;
        if (j == 1) {  // the first column's rows and v's own second unknown
            inner.reserve(inner.size() + (outer[c] - outer[c - 1]) + 1);
            for (int k = outer[c - 1]; k < outer[c]; ++k) inner.push_back(inner[k]);
            inner.push_back(c);
            continue;
        }
        firsts.clear();
        for (int s = corner_start_[o]; s < corner_start_[o + 1]; ++s)
            for (int v : faces[corner_[s] / 3])
                if (dof[v].n > 0 && dof[v].first <= dv.first) firsts.push_back(dof[v].first);
        std::sort(firsts.begin(), firsts.end());
        firsts.erase(std::unique(firsts.begin(), firsts.end()), firsts.end());
        for (int r : firsts) {
            const int n = r == dv.first ? 1 : owner_dof_[column_of[r]].n;  // v itself: only row c here
            for (int i = 0; i < n; ++i) inner.push_back(r + i);
        }
        for (int s = corner_start_[o]; s < corner_start_[o + 1]; ++s)
            for (int a = 0; a < 3; ++a) {
                const Dof& dw = dof[faces[corner_[s] / 3][a]];
                if (dw.n > 0 && dw.first <= dv.first)
                    neighbour_[3 * s + a] = owner_of[faces[corner_[s] / 3][a]],
                    rank_[3 * s + a] = int(std::lower_bound(inner.begin() + outer[c], inner.end(), dw.first) -
                                           (inner.begin() + outer[c]));
            }
    }
    outer[unknowns] = int(inner.size());
    K_.resize(unknowns, unknowns);
    K_.resizeNonZeros(Eigen::Index(inner.size()));
    std::copy(outer.begin(), outer.end(), K_.outerIndexPtr());
    std::copy(inner.begin(), inner.end(), K_.innerIndexPtr());
    std::fill(K_.valuePtr(), K_.valuePtr() + inner.size(), 0.0);
    const int* kouter = K_.outerIndexPtr();
    const int* kinner = K_.innerIndexPtr();
    for (int c = 0; c < unknowns; ++c)
        diag_[c] = int(std::lower_bound(kinner + kouter[c], kinner + kouter[c + 1], c) - kinner);
}

namespace {

/// weight A_f dPsi/dJ g_a per corner, with g the corners' weight gradients.
void corner_gradients(const FaceNewton& L, const Vec2 g[3], double w, Vec2 gradient[3]) {
    for (int a = 0; a < 3; ++a) gradient[a] = w * (L.dpsi * g[a]);
}

}  // namespace

void face_gradient(const FaceFrame& F, const FaceNewton& L, double weight, Vec2 gradient[3]) {
    if (!(F.area > 0)) {
        for (int a = 0; a < 3; ++a) gradient[a].setZero();
        return;
    }
    Vec2 g[3];
    face_gradients(F, g);
    corner_gradients(L, g, weight * F.area, gradient);
}

FaceHessian face_hessian(const FaceFrame& F, const FaceNewton& L, double weight) {
    FaceHessian h;
    if (!(F.area > 0)) {
        for (Mat2& m : h.block) m.setZero();
        for (Vec2& g : h.gradient) g.setZero();
        return h;
    }
    Vec2 g[3];
    face_gradients(F, g);
    const double w = weight * F.area;
    corner_gradients(L, g, w, h.gradient);
    Vec2 eg[4][3];  // E_i g_k
    for (int i = 0; i < 4; ++i)
        for (int k = 0; k < 3; ++k) eg[i][k] = L.mode[i] * g[k];
    for (int a = 0, s = 0; a < 3; ++a)
        for (int b = 0; b <= a; ++b, ++s) {
            Mat2 H = Mat2::Zero();
            for (int i = 0; i < 4; ++i) H += (w * L.lambda[i]) * eg[i][a] * eg[i][b].transpose();
            h.block[s] = H;
        }
    return h;
}

void NewtonSystem::assemble(const std::vector<FaceHessian>& local, bool hessian, Eigen::VectorXd& rhs,
                            bool parallel) {
    double* value = K_.valuePtr();
    const int* outer = K_.outerIndexPtr();
    auto column = [&](int o) {
        const Dof& dv = owner_dof_[o];
        for (int j = 0; j < dv.n; ++j) rhs[dv.first + j] = 0;
        if (hessian) std::fill(value + outer[dv.first], value + outer[dv.first + dv.n], 0.0);
        for (int s = corner_start_[o]; s < corner_start_[o + 1]; ++s) {
            const int f = corner_[s] / 3, b = corner_[s] % 3;
            const FaceHessian& h = local[f];
            if (hessian)
                for (int a = 0; a < 3; ++a) {
                    const int r = rank_[3 * s + a];
                    if (r < 0) continue;
                    const Dof& dw = owner_dof_[neighbour_[3 * s + a]];
                    const Mat2 H = h.at(a, b);
                    if (dv.n == 2 && dw.n == 2) {  // free vertices: the block as it is
                        double* c0 = value + outer[dv.first] + r;
                        double* c1 = value + outer[dv.first + 1] + r;
                        c0[0] += H(0, 0);
                        if (a != b) c0[1] += H(1, 0);  // the diagonal block's (1, 0) is below it
                        c1[0] += H(0, 1);
                        c1[1] += H(1, 1);
                        continue;
                    }
                    for (int j = 0; j < dv.n; ++j) {
                        double* col = value + outer[dv.first + j] + r;
                        for (int i = 0; i < dw.n; ++i)
                            if (dw.first + i <= dv.first + j) col[i] += dw.column(i).dot(H * dv.column(j));
                    }
                }
            for (int j = 0; j < dv.n; ++j) rhs[dv.first + j] -= dv.column(j).dot(h.gradient[b]);
        }
    };
    const int no = int(owner_dof_.size());
    if (parallel) tbb::parallel_for(0, no, column);
    else for (int o = 0; o < no; ++o) column(o);
}

}  // namespace ctmap

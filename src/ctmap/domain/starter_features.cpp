#include "ctmap/domain/starter_features.h"

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "ctmap/border_loop.h"
#include "ctmap/cut/work_mesh.h"
#include "ctmap/errors.h"

namespace ctmap {

std::vector<Vec2> tutte_map(const TriMesh& mesh) {
    const WorkMesh wm(mesh);
    const std::vector<int> loop = wm.border_loop();
    const int n = mesh.num_vertices();
    std::vector<Vec2> uv(n, Vec2::Zero());
    std::vector<double> acc{0};
    for (std::size_t i = 0; i < loop.size(); ++i)
        acc.push_back(acc.back() + (mesh.positions[loop[(i + 1) % loop.size()]] - mesh.positions[loop[i]]).norm());
    std::vector<char> fixed(n, 0);
    for (std::size_t i = 0; i < loop.size(); ++i) {
        const double a = 2 * M_PI * acc[i] / acc.back();
        uv[loop[i]] = Vec2(std::cos(a), std::sin(a));
        fixed[loop[i]] = 1;
    }
    std::vector<int> index(n, -1);
    int m = 0;
    for (int v = 0; v < n; ++v)
        if (!fixed[v]) index[v] = m++;
    std::vector<Eigen::Triplet<double>> trip;
    std::vector<int> degree(n, 0);
    Eigen::MatrixX2d rhs = Eigen::MatrixX2d::Zero(m, 2);
    for (std::size_t e = 0; e < wm.edges.size(); ++e) {
        const int a = key_lo(wm.edges[e]), b = key_hi(wm.edges[e]);
        for (auto [v, w] : {std::pair{a, b}, std::pair{b, a}}) {
            if (fixed[v]) continue;
            ++degree[v];
            if (fixed[w]) rhs.row(index[v]) += uv[w].transpose();
            else trip.emplace_back(index[v], index[w], -1.0);
        }
    }
    for (int v = 0; v < n; ++v)
        if (!fixed[v]) trip.emplace_back(index[v], index[v], double(degree[v]));
    Eigen::SparseMatrix<double> L(m, m);
    L.setFromTriplets(trip.begin(), trip.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(L);
    if (solver.info() != Eigen::Success) throw SolverError("tutte_map: the Laplacian could not be factorized");
    const Eigen::MatrixX2d x = solver.solve(rhs);
    for (int v = 0; v < n; ++v)
        if (!fixed[v]) uv[v] = x.row(index[v]).transpose();
    return uv;
}

std::vector<Vec2> spread_radially(const TriMesh& mesh, std::vector<Vec2> disc) {
    const int n = mesh.num_vertices();
    std::vector<double> area(n, 0);
    for (const Tri& t : mesh.faces) {
        const double a = (mesh.positions[t[1]] - mesh.positions[t[0]]).cross(mesh.positions[t[2]] - mesh.positions[t[0]]).norm();
        for (int v : t) area[v] += a / 6;
    }
    std::vector<int> order(n);
    for (int v = 0; v < n; ++v) order[v] = v;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return disc[a].norm() < disc[b].norm(); });
    double total = 0;
    for (double a : area) total += a;
    if (!(total > 0)) return disc;
    // f(r): the square root of the area share inside radius r, made strictly increasing (the
    // half of a vertex's own share, so ties and zero areas still get distinct radii) and 1 on
    // the circle, where Tutte put the border.
    double below = 0;
    std::vector<double> f(n);
    for (int i = 0; i < n; ++i) {
        const int v = order[i];
        f[v] = std::sqrt(std::clamp((below + 0.5 * area[v] + 1e-12 * (i + 1)) / (total + 1e-12 * (n + 1)), 0.0, 1.0));
        below += area[v];
    }
    for (int v = 0; v < n; ++v) {
        const double r = disc[v].norm();
        if (r >= 1 - 1e-12) continue;  // the border stays on the circle
        if (r > 0) disc[v] *= std::min(f[v], 1 - 1e-9) / r;
    }
    return disc;
}

FeatureSet starter_features(const TriMesh& mesh, int width, int height, const StarterOptions& opt,
                            const std::vector<int>* border_vertices) {
    // Tutte's map spread radially so that the 3D area is even over the disc: Tutte's own crowds
    // the interior of a curved mesh into the middle (landmarks 40 pixels apart on a 512 image).
    const std::vector<Vec2> disc = spread_radially(mesh, tutte_map(mesh));
    const std::vector<int> loop = border_loop(mesh);
    FeatureSet fs;
    fs.image_size = std::array<int, 2>{width, height};
    // The disc onto an ellipse inside the image; v up in the disc, y down in pixels (DESIGN §3).
    const double rx = 0.5 * width * (1 - 2 * opt.margin), ry = 0.5 * height * (1 - 2 * opt.margin);
    auto pixel = [&](int v) { return Vec2(0.5 * width + rx * disc[v].x(), 0.5 * height - ry * disc[v].y()); };
    // Border: equally spaced by arc length along the loop.
    std::vector<double> acc{0};
    for (std::size_t i = 0; i + 1 < loop.size(); ++i)
        acc.push_back(acc.back() + (mesh.positions[loop[i + 1]] - mesh.positions[loop[i]]).norm());
    const double total = acc.back() + (mesh.positions[loop.front()] - mesh.positions[loop.back()]).norm();
    const int nb = border_vertices ? int(border_vertices->size()) : std::clamp(opt.border, 0, int(loop.size()));
    std::vector<int> chosen;
    if (border_vertices) chosen = *border_vertices;
    for (int k = 0; k < nb && !border_vertices; ++k) {
        const double s = total * k / nb;
        const int i = int(std::lower_bound(acc.begin(), acc.end(), s) - acc.begin());
        const int v = loop[std::min<int>(i, int(loop.size()) - 1)];
        if (std::find(chosen.begin(), chosen.end(), v) == chosen.end()) chosen.push_back(v);
    }
    for (std::size_t k = 0; k < chosen.size(); ++k)
        fs.features.push_back({"border" + std::to_string(k), chosen[k], std::nullopt, pixel(chosen[k])});
    // Interior: farthest-point sampling in 3D, kept off the border polygon by staying inside a
    // disc of radius 0.85 (the border features' polygon contains it for 8 or more of them).
    std::vector<char> on_border(mesh.num_vertices(), 0);
    for (int v : loop) on_border[v] = 1;
    // With border features, the interior ones stay inside their polygon (so that the set also
    // holds with --border given); landmarks only (border 0) lie anywhere inside the disc.
    const double inner = nb == 0 ? 0.97 : nb >= 8 ? 0.85 : 0.4;
    std::vector<int> candidates;
    for (int v = 0; v < mesh.num_vertices(); ++v)
        if (!on_border[v] && disc[v].norm() < inner) candidates.push_back(v);
    std::vector<double> dist(mesh.num_vertices(), std::numeric_limits<double>::infinity());
    auto update = [&](int s) {
        for (int v : candidates) dist[v] = std::min(dist[v], (mesh.positions[v] - mesh.positions[s]).norm());
    };
    for (int v : chosen) update(v);
    for (int k = 0; k < opt.interior && !candidates.empty(); ++k) {
        const int v = *std::max_element(candidates.begin(), candidates.end(), [&](int a, int b) { return dist[a] < dist[b]; });
        if (!(dist[v] > 0)) break;
        fs.features.push_back({"landmark" + std::to_string(k), v, std::nullopt, pixel(v)});
        update(v);
    }
    return fs;
}

}  // namespace ctmap

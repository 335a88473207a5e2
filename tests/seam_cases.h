#pragma once
// Layouts whose seams ctmap must choose (issue 40, must-shows 1 and 2): the seam the user meant is
// a loop of mesh edges (where a random plane cuts a closed mesh in two, or the border of a random
// stretched geodesic disc); a few to 20 seam features lie on it, spaced unevenly, and interior
// features lie near it as well as far from it. Each chart's image points are the images of its
// disc under a one-to-one map (Tutte's, spread by area and twisted per chart, mirrored at
// random), so a valid map exists: the straight route between two seam features may pass on the
// other side of an interior feature, but the loop meant keeps every feature on its side.
#include <algorithm>
#include <map>
#include <optional>
#include <queue>
#include <random>
#include <set>
#include <string>

#include "ctmap/border_loop.h"
#include "ctmap/cut/seam_paths.h"
#include "ctmap/edge_key.h"
#include "ctmap/domain/starter_features.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/map_charts.h"
#include "random_features.h"

namespace ctmap::test {

/// Faces of a mesh as a mesh of their own.
struct FaceDisc {
    TriMesh mesh;
    std::vector<int> global;  ///< per vertex of `mesh`, its vertex in the whole mesh
};

/// The faces with `in[f]` as a mesh, if they form a manifold disc.
inline std::optional<FaceDisc> face_disc(const TriMesh& mesh, const std::vector<char>& in) {
    FaceDisc d;
    std::vector<int> local(mesh.num_vertices(), -1);
    for (int f = 0; f < mesh.num_faces(); ++f) {
        if (!in[f]) continue;
        Tri t;
        for (int k = 0; k < 3; ++k) {
            int& l = local[mesh.faces[f][k]];
            if (l < 0) l = int(d.global.size()), d.global.push_back(mesh.faces[f][k]), d.mesh.positions.push_back(mesh.positions[mesh.faces[f][k]]);
            t[k] = l;
        }
        d.mesh.faces.push_back(t);
    }
    if (d.mesh.faces.empty() || !compute_topology(d.mesh).is_disc) return std::nullopt;
    return d;
}

/// Per face, its neighbours across edges.
inline std::vector<std::vector<int>> face_neighbours(const TriMesh& mesh) {
    std::map<std::uint64_t, std::vector<int>> by_edge;
    for (int f = 0; f < mesh.num_faces(); ++f)
        for (int k = 0; k < 3; ++k) by_edge[edge_key(mesh.faces[f][k], mesh.faces[f][(k + 1) % 3])].push_back(f);
    std::vector<std::vector<int>> out(mesh.num_faces());
    for (const auto& [e, fs] : by_edge)
        if (fs.size() == 2) out[fs[0]].push_back(fs[1]), out[fs[1]].push_back(fs[0]);
    return out;
}

/// `in` reduced to its largest connected part (faces across edges).
inline void keep_largest_part(const std::vector<std::vector<int>>& nb, std::vector<char>& in) {
    std::vector<int> part(in.size(), -1), size;
    for (std::size_t f0 = 0; f0 < in.size(); ++f0) {
        if (!in[f0] || part[f0] >= 0) continue;
        const int id = int(size.size());
        size.push_back(0);
        std::vector<int> stack{int(f0)};
        part[f0] = id;
        while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            ++size[id];
            for (int g : nb[f])
                if (in[g] && part[g] < 0) part[g] = id, stack.push_back(g);
        }
    }
    if (size.empty()) return;
    const int best = int(std::max_element(size.begin(), size.end()) - size.begin());
    for (std::size_t f = 0; f < in.size(); ++f) in[f] = in[f] && part[f] == best;
}

/// One chart on `disc`: border features at `seam` (whole-mesh vertices on the disc's border, in
/// order), up to `interior` interior features (about half within 3 edges of the border), image
/// points from Tutte's map twisted by `strength`, mirrored if `mirror`.
inline ChartInput chart_on_disc(const std::string& name, const FaceDisc& disc, const std::vector<int>& seam,
                                const std::vector<std::string>& seam_names, int interior, double strength, bool mirror,
                                std::mt19937& rng) {
    const std::vector<Vec2> tutte = spread_radially(disc.mesh, tutte_map(disc.mesh));
    std::map<int, int> local;
    for (std::size_t v = 0; v < disc.global.size(); ++v) local[disc.global[v]] = int(v);
    auto image = [&](int v) {
        Vec2 p = twist(tutte[v], strength);
        if (mirror) p.x() = -p.x();
        return Vec2(0.5 + 0.45 * p.x(), 0.5 + 0.45 * p.y());
    };
    ChartInput ch;
    ch.name = name;
    std::vector<Vec2> polygon;
    for (std::size_t i = 0; i < seam.size(); ++i) {
        MapFeature f;
        f.name = seam_names[i];
        f.vertex = seam[i];
        f.uv = image(local.at(seam[i]));
        polygon.push_back(f.uv);
        ch.features.push_back(f);
        ch.border.push_back(f.name);
    }
    // Hops from the disc's border, for features near the seam.
    const int n = disc.mesh.num_vertices();
    std::vector<std::vector<int>> nb(n);
    for (const Tri& t : disc.mesh.faces)
        for (int k = 0; k < 3; ++k) nb[t[k]].push_back(t[(k + 1) % 3]), nb[t[(k + 1) % 3]].push_back(t[k]);
    std::vector<int> hops(n, -1);
    std::queue<int> queue;
    for (int v : border_loop(disc.mesh)) hops[v] = 0, queue.push(v);
    while (!queue.empty()) {
        const int v = queue.front();
        queue.pop();
        for (int w : nb[v])
            if (hops[w] < 0) hops[w] = hops[v] + 1, queue.push(w);
    }
    std::vector<int> near, far;
    for (int v = 0; v < n; ++v)
        if (hops[v] >= 1) (hops[v] <= 3 ? near : far).push_back(v);
    std::shuffle(near.begin(), near.end(), rng);
    std::shuffle(far.begin(), far.end(), rng);
    std::vector<int> candidates;  // near and far taken in turn
    for (std::size_t i = 0; i < std::max(near.size(), far.size()); ++i) {
        if (i < near.size()) candidates.push_back(near[i]);
        if (i < far.size()) candidates.push_back(far[i]);
    }
    int added = 0;
    for (int v : candidates) {
        if (added >= interior) break;
        const Vec2 q = image(v);
        bool clear = clear_inside(polygon, q);
        for (const MapFeature& f : ch.features) clear = clear && (f.uv - q).norm() >= 1e-3;
        if (!clear) continue;
        MapFeature f;
        f.name = name + "_" + std::to_string(added++);
        f.vertex = disc.global[v];
        f.uv = q;
        ch.features.push_back(f);
    }
    return ch;
}

/// `count` positions of a loop of `n` vertices, spaced unevenly (at random, at least 2 apart), in order.
inline std::vector<int> uneven_positions(int n, int count, std::mt19937& rng) {
    count = std::max(3, std::min(count, n / 3));
    for (;;) {
        std::set<int> picked;
        while (int(picked.size()) < count) picked.insert(int(rng() % n));
        std::vector<int> out(picked.begin(), picked.end());
        bool spaced = true;
        for (std::size_t i = 0; i < out.size(); ++i) {
            const int gap = (out[(i + 1) % out.size()] - out[i] + n) % n;
            spaced = spaced && (gap >= 2 || out.size() == 1);
        }
        if (spaced) return out;
    }
}

/// A layout whose seams ctmap chooses; `loop` is the seam meant (whole-mesh vertices).
struct SeamCase {
    std::vector<ChartInput> charts;
    std::vector<int> loop;
    int seam_features = 0;
};

/// Border features on `disc`'s border loop (in its order), `count` of them unevenly spaced.
inline std::vector<int> seam_on(const FaceDisc& disc, int count, std::mt19937& rng, std::vector<int>& loop) {
    loop.clear();
    for (int v : border_loop(disc.mesh)) loop.push_back(disc.global[v]);
    std::vector<int> seam;
    for (int i : uneven_positions(int(loop.size()), count, rng)) seam.push_back(loop[i]);
    return seam;
}

/// seam0, seam1, ...: the seam features' names.
inline std::vector<std::string> seam_names(std::size_t n) {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < n; ++i) out.push_back("seam" + std::to_string(i));
    return out;
}

/// Two charts on a closed mesh cut by a random plane into two discs (nullopt when the plane's
/// two sides are not both discs: the caller draws again).
inline std::optional<SeamCase> plane_two_chart_case(const TriMesh& mesh, std::mt19937& rng) {
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> unit(0, 1);
    Vec3 n(gauss(rng), gauss(rng), gauss(rng));
    n.normalize();
    double lo = 1e300, hi = -1e300;
    for (const Vec3& p : mesh.positions) lo = std::min(lo, n.dot(p)), hi = std::max(hi, n.dot(p));
    const double offset = lo + (hi - lo) * (0.3 + 0.4 * unit(rng));
    const std::vector<std::vector<int>> nb = face_neighbours(mesh);
    std::vector<char> front(mesh.num_faces());
    for (int f = 0; f < mesh.num_faces(); ++f) {
        const Tri& t = mesh.faces[f];
        front[f] = n.dot(mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3 > offset;
    }
    keep_largest_part(nb, front);
    std::vector<char> back(front.size());
    for (std::size_t f = 0; f < front.size(); ++f) back[f] = !front[f];
    const auto a = face_disc(mesh, front), b = face_disc(mesh, back);
    if (!a || !b) return std::nullopt;
    SeamCase out;
    const std::vector<int> seam = seam_on(*a, 3 + int(rng() % 18), rng, out.loop);
    if (out.loop.size() < 12) return std::nullopt;
    const std::vector<std::string> names = seam_names(seam.size());
    out.seam_features = int(seam.size());
    out.charts.push_back(chart_on_disc("front", *a, seam, names, int(rng() % 13), 3.0 * unit(rng), false, rng));
    out.charts.push_back(chart_on_disc("back", *b, seam, names, int(rng() % 13), 3.0 * unit(rng), rng() % 3 == 0, rng));
    return out;
}

/// One chart on a random stretched geodesic disc of `mesh` (any manifold: borders, handles) and
/// the rest in no chart (nullopt when the disc drawn touches the mesh border or is no disc).
inline std::optional<SeamCase> disc_chart_case(const TriMesh& mesh, std::mt19937& rng) {
    std::normal_distribution<double> gauss;
    std::uniform_real_distribution<double> unit(0, 1);
    const int nf = mesh.num_faces();
    Vec3 dir(gauss(rng), gauss(rng), gauss(rng));
    dir.normalize();
    const double stretch = 3 * unit(rng);
    // Faces by a stretched distance from a random face, up to a share of the mesh.
    const std::vector<std::vector<int>> nb = face_neighbours(mesh);
    auto centre = [&](int f) {
        const Tri& t = mesh.faces[f];
        return Vec3((mesh.positions[t[0]] + mesh.positions[t[1]] + mesh.positions[t[2]]) / 3);
    };
    std::vector<double> dist(nf, 1e300);
    const int seed = int(rng() % nf);
    using Item = std::pair<double, int>;
    std::priority_queue<Item, std::vector<Item>, std::greater<>> queue;
    dist[seed] = 0;
    queue.push({0, seed});
    std::vector<char> in(nf, 0);
    const int want = int(nf * (0.08 + 0.3 * unit(rng)));
    int taken = 0;
    while (!queue.empty() && taken < want) {
        const auto [d, f] = queue.top();
        queue.pop();
        if (d > dist[f] || in[f]) continue;
        in[f] = 1, ++taken;
        for (int g : nb[f]) {
            const Vec3 e = centre(g) - centre(f);
            const double nd = d + e.norm() * (1 + stretch * std::abs(e.normalized().dot(dir)));
            if (nd < dist[g]) dist[g] = nd, queue.push({nd, g});
        }
    }
    const auto a = face_disc(mesh, in);
    if (!a) return std::nullopt;
    const MeshTopology whole = compute_topology(mesh);
    if (whole.border_edges > 0) {  // the chart's border must be a seam, off the mesh border
        const SeamGraph graph(mesh);
        for (int v : border_loop(a->mesh))
            if (graph.on_border[a->global[v]]) return std::nullopt;
    }
    SeamCase out;
    const std::vector<int> seam = seam_on(*a, 3 + int(rng() % 18), rng, out.loop);
    if (out.loop.size() < 12) return std::nullopt;
    const std::vector<std::string> names = seam_names(seam.size());
    out.seam_features = int(seam.size());
    out.charts.push_back(chart_on_disc("face", *a, seam, names, 1 + int(rng() % 12), 3.0 * unit(rng), rng() % 3 == 0, rng));
    return out;
}

}  // namespace ctmap::test

// Experiment harness for the distortion optimiser (issue 11, must-show 4): the relaxed map of a
// scaling row (the mesh subdivided `--levels` times, `--features` random feasible features with
// `--twist`), cached in /tmp, then how its excess energy is spread over the faces, and the
// optimiser on it with a per-iteration trace (ms, energy) and a hash of the final map (to check
// that a change keeps the same bits). `--local-rounds K`: first K optimisations restricted to the
// faces holding `--hot` of the excess energy grown by `--rings`, `--local-iterations` each
// (measured on x64 in BENCHMARKS "Speed targets").
//   isometric_probe MESH [--levels L] [--features N] [--twist T] [--seed S] [--iterations I]
//                   [--local-rounds K --hot F --rings R --local-iterations I]
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

#include "ctmap/certify/certificate.h"
#include "ctmap/face_jacobian.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "ctmap/refine/face_newton.h"
#include "ctmap/border_loop.h"
#include "ctmap/subdivide.h"
#include "ctmap/refine/isometric.h"
#include "random_features.h"

using namespace ctmap;
using Clock = std::chrono::steady_clock;
static double ms_since(Clock::time_point t0) {
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

template <class T>
static void wr(std::ofstream& f, const std::vector<T>& v) {
    std::size_t n = v.size();
    f.write((const char*)&n, sizeof n);
    f.write((const char*)v.data(), n * sizeof(T));
}
template <class T>
static void rd(std::ifstream& f, std::vector<T>& v) {
    std::size_t n;
    f.read((char*)&n, sizeof n);
    v.resize(n);
    f.read((char*)v.data(), n * sizeof(T));
}

/// The scale that gives the mesh the map's UV area (the optimiser's default, IsometricOptions::scale).
static double area_scale(const TriMesh& mesh, const std::vector<Vec2>& uv) {
    double a3 = 0, a2 = 0;
    for (auto& t : mesh.faces) {
        a3 += face_frame(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]).area;
        Vec2 q1 = uv[t[1]] - uv[t[0]], q2 = uv[t[2]] - uv[t[0]];
        a2 += 0.5 * std::abs(q1.x() * q2.y() - q1.y() * q2.x());
    }
    return std::sqrt(a2 / a3);
}

/// Per face: its area times (symmetric Dirichlet density - 4), the mesh scaled by `k`; `area` gets
/// the scaled total area.
static std::vector<double> excess_energy(const TriMesh& mesh, const std::vector<Vec2>& uv, double k, double* area = nullptr) {
    const auto& f0 = mesh.faces[0];
    const int sig = orientation_2d(uv[f0[0]], uv[f0[1]], uv[f0[2]]);
    std::vector<double> ex;
    double a = 0;
    for (auto& t : mesh.faces) {
        FaceFrame F = face_frame(k * mesh.positions[t[0]], k * mesh.positions[t[1]], k * mesh.positions[t[2]], sig < 0);
        ex.push_back(F.area > 0 ? F.area * (symmetric_dirichlet_density(face_jacobian(F, uv[t[0]], uv[t[1]], uv[t[2]])) - 4) : 0);
        a += F.area;
    }
    if (area) *area = a;
    return ex;
}

int main(int argc, char** argv) {
    std::string path = argv[1];
    int levels = 0, features = 50, seed = 1, rounds = 0, iterations = 1000, rings = 3, local_iterations = 30;
    double hot = 0;
    double twist = 1.0;
    double progressive = 0;
    for (int i = 2; i + 1 < argc; i += 2) {
        std::string a = argv[i];
        if (a == "--levels") levels = std::stoi(argv[i + 1]);
        if (a == "--features") features = std::stoi(argv[i + 1]);
        if (a == "--seed") seed = std::stoi(argv[i + 1]);
        if (a == "--local-rounds") rounds = std::stoi(argv[i + 1]);
        if (a == "--hot") hot = std::stod(argv[i + 1]);
        if (a == "--rings") rings = std::stoi(argv[i + 1]);
        if (a == "--local-iterations") local_iterations = std::stoi(argv[i + 1]);
        if (a == "--iterations") iterations = std::stoi(argv[i + 1]);
        if (a == "--twist") twist = std::stod(argv[i + 1]);
        if (a == "--progressive") progressive = std::stod(argv[i + 1]);
    }
    const std::string base = path.substr(path.find_last_of('/') + 1);
    const std::string cache = "/tmp/probe_" + base + "_" + std::to_string(levels) + "_" + std::to_string(features) + "_" +
                              std::to_string(seed) + "_" + std::to_string(twist) + ".bin";
    TriMesh mesh;
    std::vector<Vec2> uv;
    std::vector<int> fixed;
    {
        std::ifstream in(cache, std::ios::binary);
        if (in) {
            rd(in, mesh.positions), rd(in, mesh.faces), rd(in, uv), rd(in, fixed);
        } else {
            const TriMesh m0 = subdivide_midpoint(read_mesh(path), levels);
            auto mf = ctmap::test::bench_features(m0, features, twist, seed);
            MapOptions options;
            options.refine_mode = RefineMode::paper;
            auto t0 = Clock::now();
            MapResult r = map_texture(m0, mf, options);
            std::fprintf(stderr, "paper pipeline %.0f ms, %d faces\n", ms_since(t0), r.cut.mesh.num_faces());
            mesh = r.cut.mesh, uv = r.uv, fixed = r.cut.feature_vertex;
            std::ofstream out(cache, std::ios::binary);
            wr(out, mesh.positions), wr(out, mesh.faces), wr(out, uv), wr(out, fixed);
        }
    }
    std::fprintf(stderr, "%d faces, %zu features\n", mesh.num_faces(), fixed.size());
    // energy distribution
    {
        double area = 0;
        std::vector<double> ex = excess_energy(mesh, uv, area_scale(mesh, uv), &area);
        double tot = 0;
        for (double e : ex) tot += e;
        std::sort(ex.rbegin(), ex.rend());
        double s = 0;
        std::size_t n = ex.size();
        std::fprintf(stderr, "SD/4 %.3f; excess share of top faces:", (tot / area + 4) / 4);
        std::size_t marks[] = {n / 10000, n / 1000, n / 100, n / 10, n / 2};
        int mi = 0;
        for (std::size_t i = 0; i < n && mi < 5; ++i) {
            s += ex[i];
            if (i + 1 == marks[mi]) std::fprintf(stderr, " top %.2f%%: %.3f", 100.0 * marks[mi] / n, s / tot), ++mi;
        }
        std::fprintf(stderr, "\n");
    }
    auto t0 = Clock::now();
    double scale = 0;
    for (int round = 0; round < rounds; ++round) {
        // hot faces: the fewest holding `hot` of the excess energy
        if (scale == 0) scale = area_scale(mesh, uv);
        const std::vector<double> per_face = excess_energy(mesh, uv, scale);
        std::vector<std::pair<double, int>> ex;
        double tot = 0;
        for (int f = 0; f < mesh.num_faces(); ++f) ex.push_back({per_face[f], f}), tot += per_face[f];
        std::sort(ex.rbegin(), ex.rend());
        std::vector<char> in(mesh.num_vertices(), 0);
        double s = 0;
        std::size_t nhot = 0;
        for (auto& [e, f] : ex) {
            if (s >= hot * tot) break;
            s += e, ++nhot;
            for (int v : mesh.faces[f]) in[v] = 1;
        }
        for (int r = 0; r < rings; ++r) {
            std::vector<char> nx = in;
            for (auto& t : mesh.faces)
                if (in[t[0]] || in[t[1]] || in[t[2]]) nx[t[0]] = nx[t[1]] = nx[t[2]] = 1;
            in.swap(nx);
        }
        IsometricOptions lo;
        lo.scale = scale;
        lo.max_iterations = local_iterations;
        for (int v = 0; v < mesh.num_vertices(); ++v)
            if (in[v]) lo.movable.push_back(v);
        auto tl = Clock::now();
        IsometricStats ls = optimise_isometric(mesh, uv, fixed, lo);
        std::fprintf(stderr, "local round %d: %zu hot faces, %zu movable, %d it, %s, %.0f ms, SD/4 %.4f -> %.4f\n", round, nhot,
                     lo.movable.size(), ls.iterations, ls.stop.c_str(), ms_since(tl), ls.energy_before() / 4, ls.energy_after() / 4);
    }
    IsometricOptions o;
    o.scale = scale;
    o.max_iterations = iterations;
    o.progressive = progressive;
    double last = 0;
    o.on_iteration = [&](int it, const std::vector<Vec2>&, double e) {
        double now = ms_since(t0);
        if (it <= 20 || it % 10 == 0) std::fprintf(stderr, "it %d  %.0f ms (+%.0f)  SD/4 %.4f\n", it, now, now - last, e / 4);
        last = now;
    };
    IsometricStats st = optimise_isometric(mesh, uv, fixed, o);
    std::size_t hash = 0;
    for (const Vec2& p : uv) hash = hash * 1000003u ^ std::hash<double>()(p.x()) ^ (std::hash<double>()(p.y()) << 1);
    std::fprintf(stderr, "uv hash %zx\n", hash);
    std::fprintf(stderr, "done: %d it, %d fact, %s, %.0f ms, SD/4 %.4f -> %.4f\n", st.iterations, st.factorisations,
                 st.stop.c_str(), ms_since(t0), st.energy_before() / 4, st.energy_after() / 4);
}


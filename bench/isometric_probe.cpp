// Experiment harness (issue 11, must-show 4): the relaxed map of a scaling row, cached in /tmp,
// then the optimiser on it with a per-iteration trace (ms, energy), optionally after local
// vertex sweeps.
//   isometric_probe MESH [--levels L] [--features N] [--seed S] [--sweeps K] [--iterations I]
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

int main(int argc, char** argv) {
    std::string path = argv[1];
    int levels = 0, features = 50, seed = 1, sweeps = 0, iterations = 1000;
    double twist = 1.0;
    for (int i = 2; i + 1 < argc; i += 2) {
        std::string a = argv[i];
        if (a == "--levels") levels = std::stoi(argv[i + 1]);
        if (a == "--features") features = std::stoi(argv[i + 1]);
        if (a == "--seed") seed = std::stoi(argv[i + 1]);
        if (a == "--sweeps") sweeps = std::stoi(argv[i + 1]);
        if (a == "--iterations") iterations = std::stoi(argv[i + 1]);
        if (a == "--twist") twist = std::stod(argv[i + 1]);
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
        double a3 = 0, a2 = 0;
        for (auto& t : mesh.faces) {
            a3 += face_frame(mesh.positions[t[0]], mesh.positions[t[1]], mesh.positions[t[2]]).area;
            Vec2 q1 = uv[t[1]] - uv[t[0]], q2 = uv[t[2]] - uv[t[0]];
            a2 += 0.5 * std::abs(q1.x() * q2.y() - q1.y() * q2.x());
        }
        double k = std::sqrt(a2 / a3);
        std::vector<double> ex;
        double tot = 0, area = 0;
        int sig = 0;
        for (auto& t : mesh.faces) {
            sig = orientation_2d(uv[t[0]], uv[t[1]], uv[t[2]]);
            break;
        }
        for (auto& t : mesh.faces) {
            FaceFrame F = face_frame(k * mesh.positions[t[0]], k * mesh.positions[t[1]], k * mesh.positions[t[2]], sig < 0);
            double e = F.area > 0 ? F.area * (symmetric_dirichlet_density(face_jacobian(F, uv[t[0]], uv[t[1]], uv[t[2]])) - 4) : 0;
            ex.push_back(e), tot += e, area += F.area;
        }
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
    IsometricOptions o;
    o.max_iterations = iterations;
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
    (void)sweeps;
}


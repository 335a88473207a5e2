// One row of the scaling table (issue 6), run in a process of its own so that its peak memory is
// its own: a real mesh (subdivided 1-to-4 `--levels` times), `--features` random feasible features
// (tests/random_features.h), ctmap's whole constrained pipeline `--runs` times (median stage
// times; file reading excluded), and in the same process CGAL's unconstrained mean value
// parameterization of the same mesh with a circular border, the yardstick. Prints one JSON object.
//
//   scaling_row MESH [--levels L] [--features N] [--runs R] [--cgal-runs K] [--seed S] [--isometric]
//
// The runs are the paper's pipeline (--refine paper); --isometric adds one run of the default
// (--refine isometric: the distortion optimiser after the relaxation, issue 11) and its figures.
//
// CGAL's time does not depend on the features, and on the largest mesh one run of it takes
// minutes, so bench/run measures it on one row per mesh (--cgal-runs 0 skips it).
#include <sys/resource.h>

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Circular_border_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/Mean_value_coordinates_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "ctmap/subdivide.h"
#include "random_features.h"

namespace {

using namespace ctmap;
using Clock = std::chrono::steady_clock;
using Kernel = CGAL::Simple_cartesian<double>;
using SM = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMP = CGAL::Surface_mesh_parameterization;

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

/// CGAL's own mean value parameterization (circular border, arc length), timed without the
/// conversion to its mesh type (ctmap's times exclude reading too). Returns milliseconds.
double cgal_mean_value_ms(const TriMesh& mesh, bool& ok) {
    SM sm;
    std::vector<SM::Vertex_index> vi;
    vi.reserve(mesh.positions.size());
    for (const Vec3& p : mesh.positions) vi.push_back(sm.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
    for (const Tri& t : mesh.faces) sm.add_face(vi[t[0]], vi[t[1]], vi[t[2]]);
    const auto t0 = Clock::now();
    const SM::Halfedge_index bhd = CGAL::Polygon_mesh_processing::longest_border(sm).first;
    auto uvmap = sm.add_property_map<SM::Vertex_index, Kernel::Point_2>("v:uv").first;
    using Border = SMP::Circular_border_arc_length_parameterizer_3<SM>;
    using Param = SMP::Mean_value_coordinates_parameterizer_3<SM, Border>;
    const SMP::Error_code err = SMP::parameterize(sm, Param(), bhd, uvmap);
    ok = err == SMP::OK;
    return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

long peak_rss_mb() {
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_maxrss / 1024;  // kilobytes on Linux
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::cerr << "usage: scaling_row MESH [--levels L] [--features N] [--runs R] [--cgal-runs K] [--seed S] [--energy-tolerance T] [--over-relaxation W] [--isometric]\n";
        return 2;
    }
    const std::string path = argv[1];
    int levels = 0, features = 10, runs = 3, cgal_runs = -1;
    unsigned seed = 1;
    double energy_tolerance = MapOptions().relax.energy_tolerance;
    double over_relaxation = MapOptions().relax.over_relaxation;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&] { return i + 1 < argc ? std::stoi(argv[++i]) : 0; };
        if (a == "--levels") levels = next();
        else if (a == "--features") features = next();
        else if (a == "--runs") runs = next();
        else if (a == "--seed") seed = unsigned(next());
        else if (a == "--cgal-runs") cgal_runs = next();
        else if (a == "--energy-tolerance" && i + 1 < argc) energy_tolerance = std::stod(argv[++i]);
        else if (a == "--over-relaxation" && i + 1 < argc) over_relaxation = std::stod(argv[++i]);
    }
    bool isometric = false;  // --isometric: also one run of the whole pipeline with --refine isometric
    for (int i = 2; i < argc; ++i)
        if (std::string(argv[i]) == "--isometric") isometric = true;
    if (cgal_runs < 0) cgal_runs = runs;
    const bool with_cgal = cgal_runs > 0;
    try {
        const TriMesh mesh = subdivide_midpoint(read_mesh(path), levels);
        const std::vector<MapFeature> mf = ctmap::test::bench_features(mesh, features, 1.0, seed);
        std::vector<double> tri, paths, embed, refine, certify, total, cgal;
        MapResult last;
        bool cgal_ok = true;
        for (int r = 0; r < runs; ++r) {
            MapOptions options;
            options.refine_mode = RefineMode::paper;  // the scaling table's figures are the paper's pipeline
            options.relax.energy_tolerance = energy_tolerance;
            options.relax.over_relaxation = over_relaxation;
            last = map_texture(mesh, mf, options);
            tri.push_back(last.timings_ms.triangulate);
            paths.push_back(last.timings_ms.paths);
            embed.push_back(last.timings_ms.embed);
            refine.push_back(last.timings_ms.refine);
            certify.push_back(last.timings_ms.certify);
            total.push_back(last.timings_ms.total);
            // Alternate with the yardstick so that both see the same machine load.
            if (r < cgal_runs) cgal.push_back(cgal_mean_value_ms(mesh, cgal_ok));
        }
        nlohmann::json j;
        j["mesh"] = path.substr(path.find_last_of('/') + 1);
        j["levels"] = levels;
        j["triangles"] = mesh.num_faces();
        j["features"] = int(mf.size());
        j["features_requested"] = features;  // a random set may come out a feature short
        j["runs"] = runs;
        j["ms"] = {{"triangulate", median(tri)}, {"paths", median(paths)}, {"embed", median(embed)},
                   {"refine", median(refine)},   {"certify", median(certify)}, {"total", median(total)}};
        j["cgal_mean_value_ms"] = with_cgal ? nlohmann::json(median(cgal)) : nlohmann::json(nullptr);
        j["cgal_runs"] = cgal_runs;
        j["cgal_ok"] = cgal_ok;
        j["ratio"] = with_cgal ? nlohmann::json(median(total) / median(cgal)) : nlohmann::json(nullptr);
        j["inserted_vertices"] = last.cut_stats.inserted_vertices;
        j["fallback_fired"] = last.cut_stats.fallback_fired;
        j["faces_out"] = last.cut.mesh.num_faces();
        j["relax_sweeps"] = last.relax_stats.iterations;
        j["valid"] = last.certificate.valid;
        j["symmetric_dirichlet"] = {last.before_refine.symmetric_dirichlet, last.certificate.distortion.symmetric_dirichlet};
        j["peak_rss_mb"] = peak_rss_mb();
        if (isometric) {
            MapOptions options;  // the default: --refine isometric
            const MapResult iso = map_texture(mesh, mf, options);
            j["isometric"] = {{"total_ms", iso.timings_ms.total},
                              {"optimise_ms", iso.timings_ms.optimise},
                              {"iterations", iso.isometric_stats.iterations},
                              {"factorisations", iso.isometric_stats.factorisations},
                              {"stop", iso.isometric_stats.stop},
                              {"valid", iso.certificate.valid},
                              {"symmetric_dirichlet", iso.certificate.distortion.symmetric_dirichlet},
                              {"peak_rss_mb", peak_rss_mb()}};
        }
        std::cout << j.dump() << std::endl;
        return last.certificate.valid ? 0 : 1;
    } catch (const std::exception& e) {
        std::cerr << "scaling_row: " << path << ": " << e.what() << "\n";
        return 3;
    }
}

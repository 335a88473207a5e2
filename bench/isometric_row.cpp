// One row of the distortion optimiser's tables (issue 11): a real mesh, a random feasible
// feature set (tests/random_features.h: `--features` N, `--twist` T, `--seed` S), ctmap's whole
// pipeline with --refine isometric, the distortion at each stage (bare embedding, the paper's
// relaxation, the optimiser), the same optimiser continued from there for a long run (2,000
// iterations in all, tolerance 1e-9: the check that the default stopped at convergence), and,
// with --arap, CGAL's unconstrained ARAP_parameterizer_3 on the same mesh timed in the same
// process, alternating with ctmap's runs. Prints one JSON object. `--landmarks`: the random set
// has no border feature, its features anywhere in the disc (issue 12, the automatic border);
// `--features-file F`: a features file (pixels, with image_size) instead of a random set.
//
//   isometric_row MESH [--features N] [--twist T] [--seed S] [--runs R] [--arap] [--no-long] [--tolerance T] [--no-reuse]
//                 [--landmarks] [--features-file F]
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/ARAP_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>

#include <algorithm>
#include <chrono>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>

#include "ctmap/errors.h"
#include "ctmap/io/features.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "random_features.h"

namespace {

using namespace ctmap;
using Clock = std::chrono::steady_clock;
using Kernel = CGAL::Simple_cartesian<double>;
using SM = CGAL::Surface_mesh<Kernel::Point_3>;
namespace SMP = CGAL::Surface_mesh_parameterization;

double ms_since(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

nlohmann::json distortion(const Distortion& d) {
    return {{"symmetric_dirichlet", d.symmetric_dirichlet}, {"conformal_mean", d.conformal_mean}};
}

/// CGAL's ARAP parameterization (free border, its defaults), timed without the conversion to its
/// mesh type. Fills the flipped count and the distortion of its map.
double cgal_arap_ms(const TriMesh& mesh, bool& ok, int& flipped, Distortion& dist) {
    SM sm;
    std::vector<SM::Vertex_index> vi;
    for (const Vec3& p : mesh.positions) vi.push_back(sm.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z())));
    for (const Tri& t : mesh.faces) sm.add_face(vi[t[0]], vi[t[1]], vi[t[2]]);
    const auto t0 = Clock::now();
    const SM::Halfedge_index bhd = CGAL::Polygon_mesh_processing::longest_border(sm).first;
    auto uvmap = sm.add_property_map<SM::Vertex_index, Kernel::Point_2>("v:uv").first;
    const SMP::Error_code err = SMP::parameterize(sm, SMP::ARAP_parameterizer_3<SM>(), bhd, uvmap);
    const double ms = ms_since(t0);
    ok = err == SMP::OK;
    std::vector<Vec2> uv(mesh.positions.size());
    for (std::size_t v = 0; v < uv.size(); ++v) uv[v] = Vec2(get(uvmap, vi[v]).x(), get(uvmap, vi[v]).y());
    const Certificate c = certify(TexturedMesh::with_vertex_uvs(mesh, uv), {}, {});
    flipped = c.flipped + c.degenerate;
    dist = c.distortion;
    return ms;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2) {
        std::cerr << "usage: isometric_row MESH [--features N] [--twist T] [--seed S] [--runs R] [--arap] [--no-long] [--tolerance T] [--no-reuse]\n"
                     "       [--progressive B] [--long-iterations N] [--no-paper]\n";
        return 2;
    }
    const std::string path = argv[1];
    int features = 20, runs = 1;
    unsigned seed = 1;
    double twist = 1.0;
    bool arap = false, long_run = true, reuse = true, landmarks = false;
    std::string features_file;
    bool paper_run = true;
    double progressive = IsometricOptions().progressive;
    int long_iterations = 2000;
    double tolerance = IsometricOptions().tolerance;
    for (int i = 2; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string("0"); };
        if (a == "--features") features = std::stoi(next());
        else if (a == "--twist") twist = std::stod(next());
        else if (a == "--seed") seed = unsigned(std::stoi(next()));
        else if (a == "--runs") runs = std::stoi(next());
        else if (a == "--arap") arap = true;
        else if (a == "--no-long") long_run = false;
        else if (a == "--tolerance") tolerance = std::stod(next());
        else if (a == "--no-reuse") reuse = false;
        else if (a == "--landmarks") landmarks = true;
        else if (a == "--features-file") features_file = next();
        else if (a == "--progressive") progressive = std::stod(next());
        else if (a == "--long-iterations") long_iterations = std::stoi(next());
        else if (a == "--no-paper") paper_run = false;
    }
    try {
        const TriMesh mesh = read_mesh(path);
        std::vector<MapFeature> mf;
        if (!features_file.empty()) {
            FeatureSet fs = read_features(features_file);
            if (!fs.image_size) throw BadInput(features_file, "isometric_row needs \"image_size\"");
            const int w = (*fs.image_size)[0], h = (*fs.image_size)[1];
            resolve_units(fs, w, h);
            mf = map_features(fs, w, h);
        } else if (landmarks) {
            std::mt19937 rng(seed);
            mf = ctmap::test::map_features_of(
                ctmap::test::random_features(mesh, tutte_map(mesh), features, 0, twist, rng, false, true));
        } else {
            mf = ctmap::test::bench_features(mesh, features, twist, seed);
        }
        std::vector<double> iso_ms, paper_ms, arap_ms;
        MapResult iso;
        bool arap_ok = true;
        int arap_flipped = 0;
        Distortion arap_dist;
        for (int r = 0; r < runs; ++r) {
            MapOptions options;
            options.isometric.tolerance = tolerance;
            options.isometric.reuse_hessian = reuse;
            options.isometric.progressive = progressive;
            iso = map_texture(mesh, mf, options);
            iso_ms.push_back(iso.timings_ms.total);
            MapOptions paper;
            paper.refine_mode = RefineMode::paper;
            if (paper_run) paper_ms.push_back(map_texture(mesh, mf, paper).timings_ms.total);
            if (arap) arap_ms.push_back(cgal_arap_ms(mesh, arap_ok, arap_flipped, arap_dist));
        }
        nlohmann::json j;
        j["mesh"] = path.substr(path.find_last_of('/') + 1);
        j["triangles"] = mesh.num_faces();
        j["faces_out"] = iso.cut.mesh.num_faces();
        j["features"] = int(mf.size());
        j["twist"] = twist;
        j["seed"] = seed;
        j["valid"] = iso.certificate.valid;
        j["auto_border_added"] = iso.auto_border.vertex.size();
        j["bare"] = distortion(iso.before_refine);
        j["paper"] = distortion(iso.after_relax);
        j["isometric"] = distortion(iso.certificate.distortion);
        j["iterations"] = iso.isometric_stats.iterations;
        j["stop"] = iso.isometric_stats.stop;
        j["line_search"] = {{"factorisations", iso.isometric_stats.factorisations},
                            {"halvings", iso.isometric_stats.halvings},
                            {"exact_rejections", iso.isometric_stats.exact_rejections},
                            {"border_rejections", iso.isometric_stats.border_rejections},
                            {"border_holds", iso.isometric_stats.border_holds}};
        j["energy"] = iso.isometric_stats.energy_after();
        j["energy_per_iteration"] = iso.isometric_stats.energy;
        j["ms"] = {{"isometric", median(iso_ms)}, {"paper", median(paper_ms)}, {"optimise", iso.timings_ms.optimise}};
        if (long_run) {
            // The same optimiser, continued from the default's map: up to `--long-iterations` (2,000) in all.
            std::vector<Vec2> uv = iso.uv;
            IsometricOptions lo;
            lo.max_iterations = std::max(0, long_iterations - iso.isometric_stats.iterations);
            lo.tolerance = 1e-9;
            lo.scale = iso.isometric_stats.scale;  // the same energy as the default's run
            const IsometricStats ls = optimise_isometric(iso.cut.mesh, uv, iso.cut.feature_vertex, lo);
            const Certificate lc = certify(TexturedMesh::with_vertex_uvs(iso.cut.mesh, uv), iso.cut.feature_vertex, iso.feature_uv);
            j["long"] = {{"iterations", iso.isometric_stats.iterations + ls.iterations},
                         {"stop", ls.stop},
                         {"energy", ls.energy_after()},
                         {"energy_per_iteration", ls.energy},
                         {"symmetric_dirichlet", lc.distortion.symmetric_dirichlet},
                         {"valid", lc.valid}};
            // The gap in the energy both runs minimise (the same scale); the certificate's
            // figures, each map scaled to its own UV area, beside it.
            j["gap"] = iso.isometric_stats.energy_after() / ls.energy_after() - 1;
            j["gap_certificate"] = iso.certificate.distortion.symmetric_dirichlet / lc.distortion.symmetric_dirichlet - 1;
        }
        if (arap) {
            j["arap"] = {{"ms", median(arap_ms)}, {"ok", arap_ok}, {"flipped", arap_flipped},
                         {"symmetric_dirichlet", arap_dist.symmetric_dirichlet}};
            j["ratio"] = median(iso_ms) / median(arap_ms);
        }
        std::cout << j.dump() << std::endl;
        return iso.certificate.valid ? 0 : 1;
    } catch (const std::exception& e) {
        std::cerr << "isometric_row: " << path << ": " << e.what() << "\n";
        return 1;
    }
}

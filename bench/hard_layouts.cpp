// Issue 17, must-show 3: the layouts the cut used to give up on or blow up with, as one JSON line
// per run: three_peaks with N random feasible features under a twist T (tests/random_features.h),
// and a mesh with every border vertex a feature plus N 3D point features placed by a one-to-one map
// (points inside faces, their image by the same barycentric mix of the Tutte map). Prints faces
// in and out, the cut's counts, the time and the certificate; a failure prints its message.
//
//   hard_layouts twist MESH N TWIST [--seed S] [--refine paper|isometric] [--guide off|on|automatic] [--obj FILE]
//                [--levels L] [--guide-subdivisions K] [--order nearest|shortest-path]
// (--levels: the mesh subdivided 1-to-4 L times before the features are drawn on it; --obj: the
// map written as OBJ; --guide-subdivisions: CutOptions::guide_subdivisions.)
//   hard_layouts points MESH N [--seed S] [--refine paper|isometric]
// (--refine paper stops after the paper's relaxation: the cut and its certificate without the
// optimiser, whose time on a mesh the cut grew to 10^5-10^6 faces is issue 11's subject.)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>

#include "ctmap/errors.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "ctmap/subdivide.h"
#include "random_features.h"

namespace {

using namespace ctmap;
using Clock = std::chrono::steady_clock;

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::cerr << "usage: hard_layouts twist MESH N TWIST [--seed S] [--refine paper|isometric] [--guide off|on|automatic] [--obj FILE] [--levels L] [--guide-subdivisions K] [--order nearest|shortest-path] | "
                     "hard_layouts points MESH N [--seed S] [--refine paper|isometric] [--guide off|on|automatic] [--obj FILE]\n";
        return 2;
    }
    const std::string kind = argv[1], mesh_file = argv[2];
    const int n = std::stoi(argv[3]);
    const double twist = kind == "twist" && argc > 4 ? std::stod(argv[4]) : 0;
    unsigned seed = 1;
    std::string refine = "isometric", guide = "automatic", obj;
    int levels = 0;  // --levels L: the input subdivided 1-to-4 L times first
    int guide_subdivisions = CutOptions().guide_subdivisions;
    std::string order = "nearest";
    for (int i = 4; i + 1 < argc; ++i) {
        if (std::string(argv[i]) == "--guide") guide = argv[i + 1];
        if (std::string(argv[i]) == "--seed") seed = unsigned(std::stoul(argv[i + 1]));
        if (std::string(argv[i]) == "--refine") refine = argv[i + 1];
        if (std::string(argv[i]) == "--obj") obj = argv[i + 1];
        if (std::string(argv[i]) == "--levels") levels = std::stoi(argv[i + 1]);
        if (std::string(argv[i]) == "--guide-subdivisions") guide_subdivisions = std::stoi(argv[i + 1]);
        if (std::string(argv[i]) == "--order") order = argv[i + 1];
    }
    const TriMesh mesh = subdivide_midpoint(read_mesh(mesh_file), levels);
    const std::vector<Vec2> tutte = test::tutte_map(mesh);
    std::mt19937 rng(seed);
    std::vector<MapFeature> features;
    if (kind == "twist") features = test::map_features_of(test::random_features(mesh, tutte, n, 12, twist, rng));
    else features = test::point_features(mesh, tutte, n, int(WorkMesh(mesh).border_loop().size()), rng);
    nlohmann::ordered_json row{{"kind", kind}, {"mesh", mesh_file}, {"features", features.size()},
                               {"twist", twist}, {"seed", seed}, {"refine", refine}, {"guide", guide},
                                   {"faces_in", mesh.num_faces()}};
    const auto t0 = Clock::now();
    try {
        MapOptions options;
        if (refine == "paper") options.refine_mode = RefineMode::paper;
        if (guide == "off") options.cut.guide = CutOptions::Guide::off;
        if (guide == "on") options.cut.guide = CutOptions::Guide::on;
        options.cut.guide_subdivisions = guide_subdivisions;
        if (order == "shortest-path") options.cut.order = CutOptions::Order::shortest_path;
        // Progress on stderr (a line per 500 paths): a long run shows where it is.
        options.progress = [t0](const std::string& stage, int done, int total) {
            if (done % 500 == 0 || done == total)
                std::cerr << stage << " " << done << "/" << total << " at "
                          << std::chrono::duration<double>(Clock::now() - t0).count() << " s" << std::endl;
        };
        const MapResult r = map_texture(mesh, features, options);
        row["faces_out"] = r.cut.mesh.num_faces();
        row["growth"] = double(r.cut.mesh.num_faces()) / mesh.num_faces();
        row["steiner_vertices"] = r.cut_stats.steiner_vertices;
        row["path_crossings_of_input_edges"] = r.cut_stats.vertices_on_input_edges;
        row["vertices_inside_input_faces"] = r.cut_stats.vertices_inside_faces;
        row["straightened_away"] = r.cut_stats.straightened_vertices;
        row["path_length"] = r.cut_stats.path_length;
        row["guided"] = r.cut_stats.guided;
        row["guide_restart_faces"] = r.cut_stats.guide_restart_faces;
        row["shortest_path_first"] = r.cut_stats.shortest_path_first;
        row["shortest_path_restart_faces"] = r.cut_stats.shortest_path_restart_faces;
        row["guide_subdivisions"] = r.cut_stats.guide_subdivisions;
        row["valid"] = r.certificate.valid;
        row["symmetric_dirichlet"] = r.certificate.distortion.symmetric_dirichlet;
        row["conformal_mean"] = r.certificate.distortion.conformal_mean;
        if (!obj.empty()) write_obj(r.textured(), obj);  // for `ctmap render --mode checker`
        row["ms"] = {{"triangulate", r.timings_ms.triangulate}, {"paths", r.timings_ms.paths}, {"embed", r.timings_ms.embed}, {"refine", r.timings_ms.refine}, {"optimise", r.timings_ms.optimise}};
    } catch (const std::exception& e) {
        row["error"] = e.what();
    }
    row["seconds"] = std::chrono::duration<double>(Clock::now() - t0).count();
    std::cout << row.dump() << std::endl;
    return row.contains("error") ? 1 : 0;
}

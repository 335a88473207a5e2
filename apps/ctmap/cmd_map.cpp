// `ctmap map`: the constrained texture map of a mesh onto an image (issue 4), written as OBJ +
// MTL, optionally GLB and a report; every output appears together or not at all.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <fstream>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "progress.h"
#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"
#include "ctmap/io/chart_features.h"
#include "ctmap/io/features.h"
#include "ctmap/io/glb_io.h"
#include "ctmap/io/image.h"
#include "ctmap/io/input_file.h"
#include "ctmap/io/map_report.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/output_paths.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "ctmap/io/printable.h"

namespace ctmap::cli {
namespace {

namespace fs = std::filesystem;

/// The first line of `ctmap map`'s output, printed as soon as the inputs are read.
void print_map_header(const MapArgs& a, std::size_t features, const MapRun& run, std::ostream& os) {
    os << "ctmap map: " << a.mesh << " with " << features << " features on "
       << (run.image.empty() ? std::string("a") : terminal_text(run.image)) << " (" << run.width << " x " << run.height << ")"
       << std::endl;
}

}  // namespace

std::string auto_border_line(const AutoBorder& added, bool kept_fixed) {
    return "border: added " + std::to_string(added.vertex.size()) + " border feature(s) (" + added.reason +
           (kept_fixed ? "); they are held where they were placed"
                       : "); they only start the border: the optimiser moves them with the free border");
}

TextureCopy texture_for_obj(const MapArgs& a, const std::string& image) {
    TextureCopy t;
    if (image.empty()) return t;
    const fs::path dir = fs::path(a.output).parent_path();
    t.upright = exif_orientation(read_input_file(image, "image file")) != 1;
    if (t.upright) {  // Blender and most OBJ viewers ignore EXIF: the UVs refer to the upright picture
        t.copy = (dir / (fs::path(a.output).stem().string() + "_texture.png")).string();
    } else if (a.copy_image) {
        const std::string beside = (dir / fs::path(image).filename()).string();
        if (!same_file(beside, image)) t.copy = beside;  // already beside the OBJ: nothing to copy
    }
    return t;
}

MapOptions map_options(const MapArgs& a) {
    MapOptions options;
    if (a.spacing > 0) options.cut.spacing_factor = a.spacing;
    options.refine = a.refine;
    options.auto_border = a.border == "auto";
    options.refine_mode = a.refine_mode == "paper" ? RefineMode::paper : RefineMode::isometric;
    options.isometric.border = a.border_mode == "fixed" ? BorderMode::fixed : BorderMode::free;
    options.isometric.keep_in_box = a.border_mode != "unbounded";
    options.isometric.max_iterations = a.iterations;
    options.isometric.tolerance = a.tolerance;
    options.snap = a.snap;
    return options;
}

std::string mtl_path_of(const MapArgs& a) {
    if (fs::path(a.output).extension() != ".obj")
        throw BadInput(a.output, "the output must be an .obj file (its .mtl is written beside it)");
    if (!a.glb.empty() && fs::path(a.glb).extension() != ".glb")
        throw BadInput(a.glb, "--glb must name a .glb file");
    return (fs::path(a.output).parent_path() / (fs::path(a.output).stem().string() + ".mtl")).string();
}

MapRun run_map(const MapArgs& a) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const std::string mtl = mtl_path_of(a);
    // Before any work: no output overwrites an input or another output, and each can be created.
    check_outputs({{a.mesh, "the mesh"}, {a.features, "the features file"}, {a.image, "the image"}},
                  {{a.output, "the output (-o)"}, {mtl, "the output's material file"}, {a.glb, "--glb"},
                   {a.report, "--report"}});
    const TriMesh mesh = read_mesh(a.mesh);
    require_disc(compute_topology(mesh), a.mesh);
    FeatureSet features = read_features(a.features);
    MapRun run;
    run.image = resolve_feature_image(features, a.image, run.width, run.height);
    run.texture = texture_for_obj(a, run.image);
    // The features file's image is an input too, and the texture copy one more output.
    check_outputs({{a.mesh, "the mesh"}, {a.features, "the features file"}, {run.image, "the image"}},
                  {{a.output, "the output (-o)"}, {mtl, "the output's material file"}, {a.glb, "--glb"},
                   {a.report, "--report"}, {run.texture.copy, "the texture copy"}});
    check_features_on_mesh(features, mesh, a.mesh, a.snap);
    if (!a.quiet) print_map_header(a, features.features.size(), run, std::cout);
    const double read_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();

    MapOptions options = map_options(a);
    Progress progress(!a.quiet, isatty(fileno(stderr)));
    options.progress = [&](const std::string& stage, int done, int total) { progress(stage, done, total); };
    run.result = naming_file(a.features,
                             [&] { return map_texture(mesh, map_features(features, run.width, run.height), options); });
    progress.clear();
    if (!a.quiet && !run.result.auto_border.vertex.empty())
        std::cout << "  " << auto_border_line(run.result.auto_border, run.result.auto_border_fixed) << std::endl;
    if (!a.quiet && run.texture.upright)
        std::cout << "  note: " << terminal_text(run.image) << " is turned by its EXIF orientation; the OBJ's material uses the "
                  << "upright copy " << run.texture.copy << std::endl;
    if (!a.quiet && run.result.point_features_moved > 0)
        std::cout << "  note: 3D point features moved onto the mesh by up to " << run.result.point_features_moved
                  << " (onto a vertex within " << snap_tolerance(mesh, a.snap)
                  << ", else to the closest point of the surface; --snap DIST)" << std::endl;
    run.result.timings_ms.read = read_ms;
    run.result.timings_ms.total += read_ms;

    // Everything is written to temporaries first and renamed together at the end.
    OutputSet outputs;
    const TexturedMesh tm = run.result.textured();
    write_obj(tm, a.output, run.texture.copy.empty() ? run.image : run.texture.copy, outputs);
    run.written = {a.output, mtl};
    if (!run.texture.copy.empty()) {
        const std::string tmp = outputs.add(run.texture.copy);
        std::ofstream os(tmp, std::ios::binary);
        if (run.texture.upright) os << encode_png(read_image(run.image));
        else os << read_input_file(run.image, "image file");
        if (!os.flush()) throw InternalError(run.texture.copy + ": could not write the texture copy");
        run.written.push_back(run.texture.copy);
    }
    if (!a.glb.empty()) {
        write_glb(tm, a.glb, run.image, outputs);
        run.written.push_back(a.glb);
    }
    if (!a.report.empty()) {
        MapReportInputs in{a.mesh, a.features, run.image, run.width, run.height, mesh.num_vertices(), mesh.num_faces()};
        const std::string tmp = outputs.add(a.report);
        write_text_file(tmp, map_report(run.result, in).dump(2) + "\n");
        run.written.push_back(a.report);
    }
    outputs.commit_all();
    return run;
}

/// A warning on stderr (even with -q) when the optimiser stopped for a reason that is not
/// convergence or the user's iteration cap: the map is valid, but not as good as it could be.
void warn_optimiser_stop(const std::string& what, const IsometricStats& is) {
    if (is.stop == "no descent step" || is.stop == "stalled" || is.stop == "border contact")
        std::cerr << "ctmap: warning: " << what << "the distortion optimiser stopped before converging (" << is.stop
                  << ", after " << is.iterations << " iterations); the map is valid\n";
}

void print_map_summary(const MapArgs& a, const MapRun& run, std::ostream& os) {
    const MapResult& r = run.result;
    const Certificate& c = r.certificate;
    const Distortion &d0 = r.before_refine, &d1 = c.distortion;
    const MapTimings& t = r.timings_ms;
    os << "  " << r.triangulation.triangles.size() << " patches, " << r.cut_stats.paths << " paths, "
       << r.cut.mesh.num_vertices() - r.cut.num_input_vertices + r.point_features << " vertices inserted ("
       << r.cut_stats.steiner_vertices << " by the fallback), " << r.cut.mesh.num_faces() << " faces\n";
    if (r.cut_stats.guided || r.cut_stats.shortest_path_first) {
        const CutStats& cs = r.cut_stats;
        os << "  note: the image twists the features against the surface";
        if (cs.guide_restart_faces > 0) os << "; the paper's cut had grown the mesh to " << cs.guide_restart_faces << " faces";
        if (cs.shortest_path_restart_faces > 0)
            os << ", shortest paths first to " << cs.shortest_path_restart_faces << " faces";
        os << "; the paths were ";
        if (cs.shortest_path_first) os << "inserted shortest first in the mesh as it stood";
        if (cs.shortest_path_first && cs.guided) os << " and ";
        if (cs.guided)
            os << "searched along the features' interpolated map"
               << (cs.guide_subdivisions > 0 ? " on the input subdivided " + std::to_string(cs.guide_subdivisions) + "x (1-to-4)"
                                             : std::string());
        os << "\n";
    }
    os << "  certificate: " << (c.valid ? "valid" : "INVALID") << " (" << c.flipped << " flipped, " << c.degenerate
       << " degenerate, feature error " << c.feature_max_error << ", border " << (c.border_simple ? "simple" : "crossing")
       << ")\n";
    const Distortion& dr = r.after_relax;
    const IsometricStats& is = r.isometric_stats;
    if (a.refine && a.refine_mode == "isometric")
        os << "  relaxation (" << r.relax_stats.iterations << " sweeps), optimiser (" << is.iterations
           << " iterations, " << a.border_mode << " border, " << (is.converged ? "converged" : "stopped") << ": " << is.stop
           << "): symmetric Dirichlet " << fixed(d0.symmetric_dirichlet, 3) << " -> " << fixed(dr.symmetric_dirichlet, 3)
           << " -> " << fixed(d1.symmetric_dirichlet, 3) << ", conformal mean " << fixed(d0.conformal_mean, 3) << " -> "
           << fixed(dr.conformal_mean, 3) << " -> " << fixed(d1.conformal_mean, 3) << "\n";
    else if (a.refine)
        os << "  refinement (" << r.relax_stats.iterations << " sweeps): symmetric Dirichlet " << fixed(d0.symmetric_dirichlet, 3)
           << " -> " << fixed(d1.symmetric_dirichlet, 3) << ", conformal mean " << fixed(d0.conformal_mean, 3) << " -> "
           << fixed(d1.conformal_mean, 3) << ", L2 stretch " << fixed(d0.l2_stretch, 3) << " -> " << fixed(d1.l2_stretch, 3)
           << "\n";
    else
        os << "  no refinement: symmetric Dirichlet " << fixed(d1.symmetric_dirichlet, 3) << ", conformal mean "
           << fixed(d1.conformal_mean, 3) << ", L2 stretch " << fixed(d1.l2_stretch, 3) << "\n";
    os << "  ms: read " << fixed(t.read, 1) << ", triangulate " << fixed(t.triangulate, 1) << ", paths " << fixed(t.paths, 1)
       << ", embed " << fixed(t.embed, 1) << ", refine " << fixed(t.refine, 1) << ", optimise " << fixed(t.optimise, 1) << ", certify " << fixed(t.certify, 1)
       << ", total " << fixed(t.total, 1) << "\n  wrote";
    for (const std::string& f : run.written) os << " " << f;
    os << "\n";
}

Command add_map_command(CLI::App& app) {
    auto args = std::make_shared<MapArgs>();
    auto* sub = app.add_subcommand(
        "map", "Map a mesh onto an image (or several: a features file with charts) with every feature exact and no "
               "flipped triangle (OBJ + MTL, GLB, report)");
    sub->add_option("MESH", args->mesh,
                    "mesh file (OFF, OBJ, PLY, STL): a topological disc, or with a features file with charts any "
                    "oriented manifold (closed, several border loops, handles; README \"Charts\")")
        ->required();
    sub->add_option("FEATURES", args->features, "features.json: the same features on the mesh and the image (README, features.json)")
        ->required();
    sub->add_option("-o,--output", args->output, "the map as OBJ; its MTL is written beside it")->required();
    sub->add_option("--image", args->image,
                    "texture image (PNG/JPEG); else the features file's \"image\", else its \"image_size\"");
    sub->add_option("--glb", args->glb, "also write binary glTF with the image embedded (three.js, Blender)");
    sub->add_option("--report", args->report, "also write a JSON report: counts, timings_ms, certificate, distortion");
    sub->add_option("--spacing", args->spacing,
                    "Steiner point spacing for the paths, as a fraction of the mean edge length (default 0.34)")
        ->check(CLI::Range(0.01, 10.0));
    sub->add_flag("--copy-image", args->copy_image,
                  "copy the image beside the OBJ, so the OBJ, MTL and image can be moved together");
    sub->add_flag("--no-refine", [args](std::int64_t) { args->refine = false; },
                  "skip the refinement (paper §2.4 and the optimiser): the bare mean value embedding");
    sub->add_option("--refine", args->refine_mode,
                    "isometric (default): the paper's relaxation (§2.4), then the distortion optimiser (symmetric "
                    "Dirichlet, every iterate certified valid, features exact); paper: the relaxation only")
        ->check(CLI::IsMember({"paper", "isometric"}));
    sub->add_option("--border", args->border,
                    "auto (default): where the given features cannot make the border (fewer than 3 on the mesh "
                    "border, or an interior feature outside their straight polygon), place border features on "
                    "the mesh border (README: the rules); given: the paper's rules, such layouts refused")
        ->check(CLI::IsMember({"auto", "given"}));
    sub->add_option("--border-mode", args->border_mode,
                    "with --refine isometric: free (default) lets the border vertices move, the border staying "
                    "simple and inside the image; fixed keeps them on the straight sides between border features; "
                    "unbounded is free without the image rectangle (UVs may leave [0, 1])")
        ->check(CLI::IsMember({"free", "fixed", "unbounded"}));
    sub->add_option("--iterations", args->iterations,
                    "the optimiser's iteration cap (default 1000; it stops earlier when converged)")
        ->check(CLI::Range(0, 1000000));
    sub->add_option("--tolerance", args->tolerance,
                    "the optimiser stops when a Newton step is predicted to lower the energy by less than this "
                    "fraction of it (default 1e-6)")
        ->check(CLI::Range(0.0, 1.0));
    sub->add_option("--snap", args->snap,
                    "how far a 3D \"point\" feature may lie off the surface, in the mesh's units (default 1e-4 of "
                    "the bounding-box diagonal); it is placed at the closest point of the surface")
        ->check(CLI::NonNegativeNumber);
    sub->add_flag("-q,--quiet", args->quiet, "print nothing on success (no header, progress or summary)");
    return {sub, [args] {
                if (has_charts(read_input_file(args->features, "features file"), args->features)) {
                    const ChartsRun run = run_map_charts(*args);
                    for (const ChartMap& c : run.result.charts)
                        warn_optimiser_stop("chart '" + c.name + "': ", c.result.isometric_stats);
                    if (!args->quiet) print_charts_summary(*args, run, std::cout);
                    return kExitOk;
                }
                const MapRun run = run_map(*args);
                warn_optimiser_stop("", run.result.isometric_stats);
                if (!args->quiet) print_map_summary(*args, run, std::cout);
                return kExitOk;
            }};
}

}  // namespace ctmap::cli

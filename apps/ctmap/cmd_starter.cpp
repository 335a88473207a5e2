// `ctmap starter-features`: a feasible features file to start from (landmarks spread over the
// mesh, placed in the image by Tutte's one-to-one map); move the image points onto the photo.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "commands.h"
#include "ctmap/domain/starter_charts.h"
#include "ctmap/domain/starter_features.h"
#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"
#include "ctmap/io/image.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/output_paths.h"
#include "ctmap/io/read_mesh.h"

namespace ctmap::cli {

namespace {

/// `starter-features --charts 2`: the two-chart file and, with `mirror`, the mirror image.
int run_starter_charts(const std::string& mesh_file, const std::string& image, const std::string& output, int seam,
                       int interior, bool mirror) {
    namespace fs = std::filesystem;
    const fs::path dir = fs::absolute(output).parent_path();
    const std::string mirrored = (dir / (fs::path(image).stem().string() + "_mirrored.png")).string();
    check_outputs({{mesh_file, "the mesh"}, {image, "the image"}},
                  {{output, "the features file (-o)"}, {mirror ? mirrored : std::string(), "the mirror image"}});
    const TriMesh mesh = read_mesh(mesh_file);
    require_manifold(compute_topology(mesh), mesh_file);
    const Image img = read_image(image);
    StarterChartsOptions opt;
    opt.seam = seam;
    opt.interior = interior;
    opt.mirror = mirror;
    std::vector<ChartFeatures> charts = naming_file(mesh_file, [&] { return starter_charts(mesh, img.width, img.height, opt); });
    charts[0].features.image = fs::relative(fs::absolute(image), dir).string();
    charts[1].features.image = mirror ? fs::path(mirrored).filename().string() : charts[0].features.image;
    OutputSet outputs;
    write_text_file(outputs.add(output), chart_features_to_json(charts) + "\n");
    if (mirror) {
        Image m = img;
        for (int y = 0; y < m.height; ++y)
            for (int x = 0; x < m.width / 2; ++x)
                for (int c = 0; c < m.channels; ++c)
                    std::swap(m.pixels[(std::size_t(y) * m.width + x) * m.channels + c],
                              m.pixels[(std::size_t(y) * m.width + (m.width - 1 - x)) * m.channels + c]);
        std::ofstream os(outputs.add(mirrored), std::ios::binary);
        os << encode_png(m);
        if (!os.flush()) throw InternalError(mirrored + ": could not write the mirror image");
    }
    outputs.commit_all();
    std::cout << "wrote " << output << ": charts 'front' and 'back' of " << mesh_file << ", " << charts[0].border.size()
              << " seam features, " << charts[0].features.features.size() - charts[0].border.size() << " and "
              << charts[1].features.features.size() - charts[1].border.size() << " landmarks, on " << image
              << (mirror ? " and its mirror image " + mirrored : std::string(" (the back chart mirrored)")) << "\n";
    return kExitOk;
}

/// starter-features on a mesh that is not a disc: one chart round a patch at its front.
int run_starter_patch(const TriMesh& mesh, const MeshTopology& topo, const std::string& mesh_file,
                      const std::string& image, const std::string& output, double patch, const StarterOptions& options) {
    namespace fs = std::filesystem;
    const Image img = read_image(image);
    std::vector<ChartFeatures> charts{
        naming_file(mesh_file, [&] { return starter_patch_chart(mesh, img.width, img.height, patch, options); })};
    charts[0].features.image = fs::relative(fs::absolute(image), fs::absolute(output).parent_path()).string();
    write_text_file(output, chart_features_to_json(charts) + "\n");
    std::cout << "wrote " << output << ": one chart 'patch' round the front of " << mesh_file << " ("
              << (topo.is_closed ? "closed" : std::to_string(topo.border_loops) + " border loops") << ", Euler characteristic "
              << topo.euler << "), " << charts[0].border.size() << " border and "
              << charts[0].features.features.size() - charts[0].border.size() << " interior features on " << image
              << "; ctmap map maps the rest of the mesh automatically\n";
    return kExitOk;
}

}  // namespace

Command add_starter_command(CLI::App& app) {
    struct Args {
        std::string mesh, image, output;
        StarterOptions options;
        int charts = 1;
        double patch = 0.3;
        int seam = 8;
        bool no_mirror = false;
    };
    auto a = std::make_shared<Args>();
    auto* sub = app.add_subcommand("starter-features",
                                   "Write a feasible features file to start from: border features equally spaced, "
                                   "interior landmarks spread out, placed in the image by a one-to-one map");
    sub->add_option("MESH", a->mesh, "mesh file: a topological disc, or with --charts 2 a closed mesh")->required();
    sub->add_option("--image", a->image, "the image the features are placed on (PNG/JPEG)")->required();
    sub->add_option("-o,--output", a->output, "features file to write (.json)")->required();
    sub->add_option("--border", a->options.border,
                    "features on the mesh border (0: landmarks only; `ctmap map` then places the border)")
        ->capture_default_str()
        ->check(CLI::Range(0, 1000));
    sub->add_option("--interior", a->options.interior, "interior features (per chart with --charts 2)")
        ->capture_default_str()
        ->check(CLI::Range(0, 100000));
    sub->add_option("--charts", a->charts,
                    "2: for a closed mesh, cut it along a seam round its middle (the plane through its centre "
                    "across its shortest side, the paper's bisection line) into a front and a back chart; the "
                    "back chart is placed on the image's mirror image, written beside the features file")
        ->capture_default_str()
        ->check(CLI::IsMember({1, 2}));
    sub->add_option("--patch", a->patch,
                    "for a mesh that is not a disc (closed, several border loops, handles) and --charts 1: one chart "
                    "round a disc of about this share of the surface at the mesh's front (+z); the rest is mapped "
                    "automatically by ctmap map")
        ->capture_default_str()
        ->check(CLI::Range(0.01, 0.95));
    sub->add_option("--seam", a->seam, "with --charts 2: features on the seam")->capture_default_str()->check(CLI::Range(3, 1000));
    sub->add_flag("--no-mirror", a->no_mirror,
                  "with --charts 2: both charts on the same image (the back chart mirrored on it) instead of the "
                  "mirror image");
    return {sub, [a] {
                if (a->options.border + a->options.interior < 1)
                    throw BadInput(a->output, "--border 0 --interior 0 asks for no feature at all");
                if (a->charts == 2) return run_starter_charts(a->mesh, a->image, a->output, a->seam, a->options.interior,
                                                              !a->no_mirror);
                check_outputs({{a->mesh, "the mesh"}, {a->image, "the image"}}, {{a->output, "the features file (-o)"}});
                const TriMesh mesh = read_mesh(a->mesh);
                const MeshTopology topo = compute_topology(mesh);
                if (!topo.is_disc && topo.is_manifold && topo.components == 1 && topo.degenerate_faces == 0)
                    return run_starter_patch(mesh, topo, a->mesh, a->image, a->output, a->patch, a->options);
                require_disc(topo, a->mesh);
                const Image img = read_image(a->image);
                FeatureSet fs = starter_features(mesh, img.width, img.height, a->options);
                // The image named relative to the features file, as DESIGN §4 resolves it.
                const auto dir = std::filesystem::absolute(a->output).parent_path();
                fs.image = std::filesystem::relative(std::filesystem::absolute(a->image), dir).string();
                write_text_file(a->output, features_to_json(fs) + "\n");
                std::cout << "wrote " << a->output << ": " << fs.features.size() << " features ("
                          << std::min<int>(a->options.border, int(fs.features.size())) << " on the border) for "
                          << a->mesh << " on " << a->image << " (" << img.width << " x " << img.height << ")\n";
                return int(kExitOk);
            }};
}

}  // namespace ctmap::cli

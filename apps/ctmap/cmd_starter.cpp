// `ctmap starter-features`: a feasible features file to start from (landmarks spread over the
// mesh, placed in the image by Tutte's one-to-one map); move the image points onto the photo.
#include <filesystem>
#include <iostream>

#include "commands.h"
#include "ctmap/domain/starter_features.h"
#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"
#include "ctmap/io/image.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/output_paths.h"
#include "ctmap/io/read_mesh.h"

namespace ctmap::cli {

Command add_starter_command(CLI::App& app) {
    struct Args {
        std::string mesh, image, output;
        StarterOptions options;
    };
    auto a = std::make_shared<Args>();
    auto* sub = app.add_subcommand("starter-features",
                                   "Write a feasible features file to start from: border features equally spaced, "
                                   "interior landmarks spread out, placed in the image by a one-to-one map");
    sub->add_option("MESH", a->mesh, "mesh file, a topological disc")->required();
    sub->add_option("--image", a->image, "the image the features are placed on (PNG/JPEG)")->required();
    sub->add_option("-o,--output", a->output, "features file to write (.json)")->required();
    sub->add_option("--border", a->options.border,
                    "features on the mesh border (0: landmarks only; `ctmap map` then places the border)")
        ->capture_default_str()
        ->check(CLI::Range(0, 1000));
    sub->add_option("--interior", a->options.interior, "interior features")->capture_default_str()->check(CLI::Range(0, 100000));
    return {sub, [a] {
                if (a->options.border + a->options.interior < 1)
                    throw BadInput(a->output, "--border 0 --interior 0 asks for no feature at all");
                check_outputs({{a->mesh, "the mesh"}, {a->image, "the image"}}, {{a->output, "the features file (-o)"}});
                const TriMesh mesh = read_mesh(a->mesh);
                require_disc(compute_topology(mesh), a->mesh);
                const Image img = read_image(a->image);
                FeatureSet fs = starter_features(mesh, img.width, img.height, a->options);
                // The image named relative to the features file, as DESIGN §4 resolves it.
                const auto dir = std::filesystem::absolute(a->output).parent_path();
                fs.image = std::filesystem::relative(std::filesystem::absolute(a->image), dir).string();
                write_text_file(a->output, features_to_json(fs) + "\n");
                std::cout << "wrote " << a->output << ": " << fs.features.size() << " features ("
                          << std::min<int>(a->options.border, int(fs.features.size())) << " on the border) for "
                          << a->mesh << " on " << a->image << " (" << img.width << " x " << img.height << ")\n";
                return kExitOk;
            }};
}

}  // namespace ctmap::cli

// ctmap's subcommands that live in their own files (apps/ctmap/cmd_<name>.cpp). Each file adds
// its subcommand to the app and returns what to run when it was chosen, so main.cpp stays a list.
#pragma once

#include <CLI/CLI.hpp>

#include <array>
#include <functional>
#include <iomanip>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/output_paths.h"
#include "ctmap/map_charts.h"
#include "ctmap/map_texture.h"

namespace ctmap::cli {

/// `x` with `digits` digits after the point (the reports' figures).
inline std::string fixed(double x, int digits) {
    std::ostringstream os;
    os << std::fixed << std::setprecision(digits) << x;
    return os.str();
}

struct Command {
    CLI::App* sub = nullptr;       ///< the subcommand, as added to the app
    std::function<int()> run;      ///< runs it after parsing; returns the exit code (DESIGN §3)
};

Command add_render_command(CLI::App& app);  // cmd_render.cpp
Command add_bake_command(CLI::App& app);    // cmd_bake.cpp

/// What `ctmap map` is asked to do (also used by `ctmap demo`).
struct MapArgs {
    std::string mesh, features, output, image, glb, report;
    double spacing = 0;  ///< 0: the cut's default
    double snap = -1;    ///< --snap: how far a point feature may be off the surface (< 0: the default)
    bool refine = true;
    std::string refine_mode = "isometric";  ///< --refine paper|isometric
    std::string border_mode = "free";       ///< --border-mode free|fixed
    std::string border = "auto";            ///< --border auto|given: place border features where needed
    int iterations = 1000;                  ///< --iterations: the optimiser's cap
    double tolerance = 1e-6;                ///< --tolerance: the optimiser's Newton decrement, relative
    bool quiet = false;
    bool copy_image = false;  ///< --copy-image: the image beside the OBJ
};

/// The image the OBJ's material names, when it is not the input image itself.
struct TextureCopy {
    std::string copy;      ///< where the copy is written (empty: the material names the input image)
    bool upright = false;  ///< a JPEG turned by EXIF: the copy is the upright picture as PNG
};

/// Which texture copy `ctmap map` writes beside the OBJ for `image`: an upright PNG for a JPEG
/// with an EXIF orientation, else a plain copy with --copy-image (unless it is already there).
TextureCopy texture_for_obj(const MapArgs& args, const std::string& image);

/// A map made and written by `run_map`.
struct MapRun {
    MapResult result;
    std::string image;  ///< the image used (empty when only image_size was given)
    TextureCopy texture;
    int width = 0, height = 0;
    std::vector<std::string> written;  ///< the files written, in order
};

/// Reads, maps (map_texture), certifies and writes OBJ + MTL (+ GLB, report) together.
/// 	hrow BadInput / InternalError as map_texture and the readers and writers; nothing is written then.
MapRun run_map(const MapArgs& args);

/// The one line that says which border features ctmap added and why (`--border auto`).
std::string auto_border_line(const AutoBorder& added, bool kept_fixed);

/// The short human summary of a map.
void print_map_summary(const MapArgs& args, const MapRun& run, std::ostream& os);

/// The pipeline's options as `ctmap map`'s arguments set them.
MapOptions map_options(const MapArgs& args);

/// The MTL file beside `-o`. \throw BadInput if -o is no .obj or --glb no .glb.
std::string mtl_path_of(const MapArgs& args);

/// A map with several charts (issue 13) made and written by `run_map_charts`.
struct ChartsRun {
    ChartsResult result;
    std::vector<std::string> images;      ///< per chart, the image used (empty when only image_size was given)
    std::vector<std::array<int, 2>> sizes;  ///< per chart, its image's width and height
    std::vector<std::string> written;     ///< the files written, in order
};

/// A charts map's inputs, read and checked as `ctmap map` and `ctmap validate` both need them.
struct ChartsInputs {
    TriMesh mesh;
    MeshTopology topology;                  ///< of `mesh`, computed once
    std::vector<ChartInput> charts;         ///< per chart, its features with UVs and its border
    std::vector<std::string> images;        ///< per chart, its image (empty when only image_size was given)
    std::vector<std::array<int, 2>> sizes;  ///< per chart, its image's width and height
};

/// Reads the mesh (any oriented manifold) and the features file with charts, resolves each
/// chart's image and checks every feature on the mesh (`snap` as --snap) and that no path of
/// `outputs` is an input. \throw BadInput / TopologyError naming the file and the problem.
ChartsInputs read_charts_inputs(const std::string& mesh_path, const std::string& features_path, double snap,
                                const std::vector<NamedPath>& outputs = {});

/// `ctmap validate` for a features file with charts: the checks `ctmap map` makes on the inputs
/// (the seams, each chart's region and layout, the cut), run as map runs them, up to the certified
/// bare embedding (no relaxation or optimiser), nothing written. Exit 0, or throws as map.
int validate_charts(const std::string& mesh_path, const std::string& features_path, const std::string& image_arg,
                    double snap, const std::string& border);

/// `ctmap map` for a features file with charts: map_charts, then OBJ + MTL with a material per
/// chart (+ GLB with a primitive per chart, report) written together. \throw as run_map.
ChartsRun run_map_charts(const MapArgs& args);

/// The short human summary of a charts map, a line per chart.
void print_charts_summary(const MapArgs& args, const ChartsRun& run, std::ostream& os);

/// `ctmap check` for a features file with charts (cmd_check_charts.cpp): exit 0 valid, 1 invalid.
int check_charts(const std::string& map_path, const std::string& features_path, bool as_json, double snap);

Command add_map_command(CLI::App& app);      // cmd_map.cpp
Command add_starter_command(CLI::App& app);  // cmd_starter.cpp
Command add_morph_command(CLI::App& app);    // cmd_morph.cpp
Command add_serve_command(CLI::App& app);    // cmd_serve.cpp

}  // namespace ctmap::cli

// ctmap: the command-line front end. Only argument parsing and printing live here; every
// capability is a library function (DESIGN §2).
#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>

#include "ctmap/certify/certificate.h"
#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"
#include "ctmap/io/printable.h"
#include "ctmap/io/data_path.h"
#include "ctmap/io/chart_features.h"
#include "ctmap/io/features.h"
#include "ctmap/io/input_file.h"
#include "ctmap/io/glb_io.h"
#include "ctmap/io/image.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/output_paths.h"
#include "ctmap/io/read_mesh.h"
#include "commands.h"
#include "ctmap/map_texture.h"
#include "ctmap/render/gallery.h"

namespace {

using namespace ctmap;
namespace fs = std::filesystem;

std::string lower_ext(const std::string& p) {
    std::string e = fs::path(p).extension().string();
    for (char& c : e) c = char(std::tolower((unsigned char)c));
    return e;
}

/// Levenshtein distance, for "did you mean" on a mistyped command.
std::size_t edit_distance(const std::string& a, const std::string& b) {
    std::vector<std::size_t> row(b.size() + 1);
    for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
    for (std::size_t i = 1; i <= a.size(); ++i) {
        std::size_t diag = row[0];
        row[0] = i;
        for (std::size_t j = 1; j <= b.size(); ++j) {
            const std::size_t up = row[j];
            row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
            diag = up;
        }
    }
    return row[b.size()];
}

int cmd_info(const std::string& mesh_path, bool as_json) {
    const TriMesh mesh = read_mesh(mesh_path);
    const MeshTopology t = compute_topology(mesh);
    if (as_json) {
        std::cout << topology_to_json(t) << "\n";
        return kExitOk;
    }
    std::cout << mesh_path << "\n"
              << "  vertices " << t.vertices << ", faces " << t.faces << ", edges " << t.edges << "\n"
              << "  components " << t.components << ", border loops " << t.border_loops << " (" << t.border_edges
              << " border edges), Euler characteristic " << t.euler << "\n"
              << "  non-manifold vertices " << t.non_manifold_vertices << ", non-manifold edges "
              << t.non_manifold_edges << ", inconsistently oriented edges " << t.inconsistent_edges << "\n"
              << "  degenerate faces " << t.degenerate_faces << ", duplicated vertices " << t.duplicated_vertices
              << ", isolated vertices " << t.isolated_vertices << "\n"
              << "  " << (t.is_disc ? "a topological disc: ready for `ctmap map`"
                          : t.is_closed ? "closed (no border): needs a seam before it can be mapped"
                                        : "not a disc: `ctmap map` needs one border loop and no handles")
              << "\n";
    return kExitOk;
}

/// `ctmap validate`: every check `ctmap map` makes before the cut, with the same verdict and
/// message (issue 17): the files, the topology, the features on the mesh and in the image, and
/// the feature layout (border features in the border's order, a simple border polygon holding
/// every interior feature).
int cmd_validate(const std::string& mesh_path, const std::string& features_path, const std::string& image_arg,
                 double snap, const std::string& border) {
    if (has_charts(read_input_file(features_path, "features file"), features_path))
        return cli::validate_charts(mesh_path, features_path, image_arg, snap, border);
    const TriMesh mesh = read_mesh(mesh_path);
    const MeshTopology t = compute_topology(mesh);
    require_disc(t, mesh_path);
    FeatureSet fs = read_features(features_path);
    int w = 0, h = 0;
    const std::string image = resolve_feature_image(fs, image_arg, w, h);
    const double moved = check_features_on_mesh(fs, mesh, mesh_path, snap);
    const FeatureLayout layout = naming_file(
        features_path, [&] { return check_feature_layout(mesh, map_features(fs, w, h), snap, border == "auto"); });
    const FeatureTriangulation& tri = layout.triangulation;
    std::cout << "ok: " << mesh_path << " is a disc (" << t.vertices << " vertices, " << t.faces << " faces); "
              << fs.features.size() << " features in " << features_path << " on a " << w << " x " << h << " image"
              << (image.empty() ? "" : " (" + image + ")") << "; " << tri.triangles.size() << " patches\n";
    if (!layout.auto_border.vertex.empty())
        std::cout << "  border: `ctmap map` adds " << layout.auto_border.vertex.size() << " border feature(s) ("
                  << layout.auto_border.reason << "; --border given refuses this layout)\n";
    if (moved > 0)
        std::cout << "  note: 3D point features lie up to " << moved << " off the surface; `ctmap map` places each "
                  << "at the closest point of the surface\n";
    return kExitOk;
}

int cmd_convert(const std::string& mesh_path, const std::string& out_path) {
    const std::string ext = lower_ext(out_path);
    if (ext != ".obj" && ext != ".glb") throw BadInput(out_path, "unknown output format '" + ext + "' (use .obj or .glb)");
    const std::string mtl = ext == ".obj" ? (fs::path(out_path).parent_path() / (fs::path(out_path).stem().string() + ".mtl")).string() : "";
    check_outputs({{mesh_path, "the mesh"}}, {{out_path, "the output (-o)"}, {mtl, "the output's material file"}});
    const TriMesh mesh = read_mesh(mesh_path);
    TexturedMesh tm;
    tm.mesh = mesh;
    tm.chart.assign(mesh.faces.size(), 0);
    if (ext == ".obj") write_obj(tm, out_path);
    else write_glb(tm, out_path);
    std::cout << "wrote " << out_path << " (" << mesh.num_vertices() << " vertices, " << mesh.num_faces()
              << " faces)\n";
    return kExitOk;
}

/// `ctmap check`: the validity certificate of any OBJ with UVs, so maps made by other tools can
/// be checked too (issue 4). Feature UVs follow `image_to_uv` on the resolved pixels, the rule
/// `ctmap map` writes with, so "exact" is bitwise. Exit 0 valid, 1 invalid.
int cmd_check(const std::string& obj_path, const std::string& features_path, const std::string& image_arg,
              bool as_json, double snap, double feature_tolerance) {
    if (has_charts(read_input_file(features_path, "features file"), features_path))
        return cli::check_charts(obj_path, features_path, as_json, snap);
    TexturedMesh tm = lower_ext(obj_path) == ".glb" ? read_glb(obj_path) : read_textured_obj(obj_path);
    // A features file without charts certifies one chart, whatever materials or primitives the
    // file splits its faces into (a Blender OBJ with two materials is one map).
    tm.chart.assign(tm.mesh.faces.size(), 0);
    if (tm.uvs.empty() || tm.uv_faces.size() != tm.mesh.faces.size())
        throw BadInput(obj_path, "no texture coordinates (`vt` and `f v/vt`): there is no map to check");
    FeatureSet fs = read_features(features_path);
    int w = 0, h = 0;
    resolve_feature_image(fs, image_arg, w, h);
    check_features_on_mesh(fs, tm.mesh, obj_path, snap);
    const std::vector<int> fv = feature_vertices_on_map(fs, tm.mesh, obj_path, snap);
    std::vector<Vec2> fuv;
    for (const Feature& f : fs.features) {
        Vec2 uv = image_to_uv(f.image, w, h);
        if (lower_ext(obj_path) == ".glb")  // glTF holds float UVs with v flipped: the rule write_glb writes with
            uv = Vec2(double(float(uv.x())), 1.0 - double(float(1.0 - uv.y())));
        fuv.push_back(uv);
    }
    Certificate c = certify(tm, fv, fuv);
    // --feature-tolerance: a map written by another program with rounded UVs (Blender's OBJ
    // exporter writes 6 decimals) holds its features to that rounding, not exactly.
    if (feature_tolerance > 0 && c.flipped == 0 && c.degenerate == 0 && c.border_simple &&
        c.feature_max_error <= feature_tolerance)
        c.valid = true;
    if (as_json) {
        std::cout << certificate_to_json(c).dump(2) << "\n";
    } else {
        const Distortion& d = c.distortion;
        std::cout << obj_path << ": " << (c.valid ? "valid" : "INVALID") << " (" << c.triangles << " triangles, "
                  << fv.size() << " features" << (c.mirrored ? ", mirrored" : "") << ")\n"
                  << "  flipped " << c.flipped << ", degenerate " << c.degenerate << ", feature error "
                  << c.feature_max_error
                  << (c.worst_feature >= 0 ? " (feature \"" + printable(fs.features[c.worst_feature].name) + "\")" : "")
                  << ", border " << (c.border_simple ? "simple" : "NOT simple (" + std::to_string(c.border_crossings) + " crossings)")
                  << "\n"
                  << "  distortion: symmetric Dirichlet " << d.symmetric_dirichlet << ", conformal mean "
                  << d.conformal_mean << " max " << d.conformal_max << ", area mean " << d.area_mean << " max "
                  << d.area_max << ", L2 stretch " << d.l2_stretch << "\n";
        if (!c.bad_faces.empty()) {
            std::cout << "  bad UV faces:";
            for (int f : c.bad_faces) std::cout << " " << f;
            std::cout << "\n";
        }
    }
    return c.valid ? kExitOk : kExitInvalid;
}

/// The shipped example, end to end (issues 4 and 5): nefertiti.off mapped with the project's
/// features onto astronaut.png, the map written as OBJ + MTL, GLB and report, then its five
/// pictures and a page that shows them (index.html), all in `out_dir`.
int cmd_demo(const std::string& out_dir) {
    cli::MapArgs args;
    args.mesh = find_data_file("meshes/nefertiti.off");
    args.features = find_data_file("features/nefertiti_astronaut.json");
    args.image = find_data_file("images/astronaut.png");
    std::error_code ec;
    fs::create_directories(out_dir, ec);
    if (ec) throw BadInput(out_dir, "cannot create the output folder (" + ec.message() + ")");
    const fs::path out(out_dir);
    args.output = (out / "nefertiti.obj").string();
    args.glb = (out / "nefertiti.glb").string();
    args.report = (out / "report.json").string();
    const cli::MapRun run = cli::run_map(args);
    cli::print_map_summary(args, run, std::cout);

    const MapResult& r = run.result;
    GalleryOptions gallery;
    gallery.title = "nefertiti on astronaut.png";
    gallery.notes = {std::to_string(r.feature_uv.size()) + " features, " + std::to_string(r.triangulation.triangles.size()) +
                         " patches, " + std::to_string(r.cut.mesh.num_faces()) + " faces",
                     std::string("certificate: ") + (r.certificate.valid ? "valid" : "INVALID") + ", " +
                         std::to_string(r.certificate.flipped) + " flipped, feature error " +
                         std::to_string(r.certificate.feature_max_error),
                     "symmetric Dirichlet " + std::to_string(r.before_refine.symmetric_dirichlet) + " -> " +
                         std::to_string(r.certificate.distortion.symmetric_dirichlet) + " after refinement",
                     "total " + std::to_string(int(r.timings_ms.total)) + " ms"};
    OutputSet pictures;
    RenderFiles files;
    files.map = args.output;
    files.image = args.image;
    files.features = args.features;
    const auto written = write_gallery(files, out_dir, "nefertiti", gallery, pictures);
    pictures.commit_all();
    std::cout << "demo: " << written.size() << " pictures and index.html in " << out_dir
              << " (open index.html in a browser)\n";
    return kExitOk;
}

int run(int argc, char** argv) {
    CLI::App app{
        "ctmap: constrained texture mapping (Guo, Wang, Cui, Peng).\n"
        "Puts every feature of a 3D disc mesh exactly on its point in a photograph, with no flipped\n"
        "triangle. Exit codes: 0 ok, 1 invalid map (check), 2 bad input, 3 internal failure.",
        "ctmap"};
    app.require_subcommand(1);
    app.set_version_flag("--version", "ctmap 0.1.0");

    std::string mesh_path, features_path, image_arg, out_path;
    bool as_json = false;
    double snap = -1;
    const char* const snap_help =
        "how far a 3D \"point\" feature may lie off the surface, in the mesh's units (default 1e-4 of the "
        "bounding-box diagonal)";

    auto* info = app.add_subcommand("info", "Print the topology of a mesh (OFF, OBJ, PLY, STL)");
    info->add_option("MESH", mesh_path, "mesh file")->required();
    info->add_flag("--json", as_json, "print JSON (keys: vertices, faces, components, border_loops, euler, ...)");

    auto* validate = app.add_subcommand("validate", "Check a mesh, a features file and an image before mapping");
    validate->add_option("MESH", mesh_path, "mesh file: a topological disc, or any oriented manifold with a features file with charts")->required();
    validate->add_option("FEATURES", features_path, "features.json: the same features on the mesh and the image (README)")->required();
    validate->add_option("--image", image_arg, "texture image (PNG/JPEG); overrides the features file's \"image\"");
    validate->add_option("--snap", snap, snap_help)->check(CLI::NonNegativeNumber);
    std::string border = "auto";
    validate->add_option("--border", border,
                         "auto (default): say which border features `ctmap map` would add where the given ones cannot "
                         "make the border; given: the paper's rules, such layouts refused")
        ->check(CLI::IsMember({"auto", "given"}));

    auto* convert = app.add_subcommand("convert", "Convert a mesh to OBJ or binary glTF (.glb)");
    convert->add_option("MESH", mesh_path, "input mesh file")->required();
    convert->add_option("-o,--output", out_path, "output file, .obj or .glb")->required();

    auto* check = app.add_subcommand("check", "Certify a texture map (OBJ or GLB with UVs): exit 0 valid, 1 invalid");
    check->add_option("MAP", mesh_path, "textured OBJ (`vt` and `f v/vt`) or binary glTF (.glb) with TEXCOORD_0")->required();
    check->add_option("--features", features_path, "features.json: the features the map must hold (README)")->required();
    check->add_option("--snap", snap, snap_help)->check(CLI::NonNegativeNumber);
    check->add_option("--image", image_arg, "texture image (PNG/JPEG); overrides the features file's \"image\"");
    check->add_flag("--json", as_json, "print the certificate as JSON");
    double feature_tolerance = 0;
    check->add_option("--feature-tolerance", feature_tolerance,
                      "accept features within this UV distance of their image points (default 0: exactly; "
                      "1e-6 for a map another program wrote with 6-decimal UVs, e.g. Blender's OBJ export)")
        ->check(CLI::NonNegativeNumber);

    std::string demo_out = "ctmap-demo";
    auto* demo = app.add_subcommand("demo", "Run ctmap on the shipped example (nefertiti + astronaut)");
    demo->add_option("--out", demo_out, "output folder")->capture_default_str();

    // Subcommands in their own files (commands.h): add one line here per file.
    const std::vector<cli::Command> commands = {
        cli::add_map_command(app),
        cli::add_render_command(app),
        cli::add_bake_command(app),
        cli::add_starter_command(app),
        cli::add_morph_command(app),
        cli::add_serve_command(app),
    };

    if (argc >= 2 && argv[1][0] != '-') {  // a mistyped command: say which one was meant
        const std::string given = argv[1];
        std::vector<std::string> names;
        for (const CLI::App* s : app.get_subcommands([](CLI::App*) { return true; })) names.push_back(s->get_name());
        if (std::find(names.begin(), names.end(), given) == names.end()) {
            std::string best;
            std::size_t best_d = 3;  // suggest only names within two edits
            for (const std::string& n : names)
                if (const std::size_t d = edit_distance(given, n); d < best_d) best_d = d, best = n;
            std::string list;
            for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
            std::cerr << "ctmap: error: unknown command " << quoted_name(given)
                      << (best.empty() ? std::string() : "; did you mean '" + best + "'?") << " (commands: " << list
                      << "; ctmap --help)\n";
            return kExitBadInput;
        }
    }
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int code = app.exit(e);
        return code == 0 ? kExitOk : kExitBadInput;
    }
    if (*info) return cmd_info(mesh_path, as_json);
    if (*validate) return cmd_validate(mesh_path, features_path, image_arg, snap, border);
    if (*convert) return cmd_convert(mesh_path, out_path);
    if (*check) return cmd_check(mesh_path, features_path, image_arg, as_json, snap, feature_tolerance);
    if (*demo) return cmd_demo(demo_out);
    for (const cli::Command& c : commands)
        if (*c.sub) return c.run();
    return kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
    try {
        return run(argc, argv);
    } catch (const ctmap::BadInput& e) {
        std::cerr << "ctmap: error: " << ctmap::terminal_text(e.what()) << "\n";
        return ctmap::kExitBadInput;
    } catch (const ctmap::InternalError& e) {
        std::cerr << "ctmap: internal failure: " << ctmap::terminal_text(e.what()) << "\n";
        return ctmap::kExitInternal;
    } catch (const std::bad_alloc&) {
        std::cerr << "ctmap: internal failure: out of memory\n";
        return ctmap::kExitInternal;
    } catch (const std::exception& e) {
        std::cerr << "ctmap: internal failure: " << ctmap::terminal_text(e.what()) << "\n";
        return ctmap::kExitInternal;
    }
}

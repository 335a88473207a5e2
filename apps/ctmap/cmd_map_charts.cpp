// `ctmap map` with a features file that has charts (issue 13): several images on one mesh,
// written as one OBJ with a material per chart (+ GLB with a primitive per chart, report).
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "commands.h"
#include "progress.h"
#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"
#include "ctmap/io/chart_features.h"
#include "ctmap/io/glb_io.h"
#include "ctmap/io/image.h"
#include "ctmap/io/input_file.h"
#include "ctmap/io/map_report.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/output_paths.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/io/printable.h"

namespace ctmap::cli {
namespace {

/// The summary's note on re-routed seam pieces, or "".
std::string rerouted_text(int pieces) {
    if (pieces == 0) return "";
    return " (" + std::to_string(pieces) +
           " traced again round a feature or off a handle, so each chart is a disc holding its features)";
}

namespace fs = std::filesystem;

/// A checker of `cells` x `cells` squares (the render's colours), for the faces in no chart.
Image checker_image(int size, int cells) {
    Image img;
    img.width = img.height = size;
    img.channels = 4;
    img.pixels.resize(std::size_t(size) * size * 4);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const bool dark = ((x * cells / size) + (y * cells / size)) % 2 == 0;
            const std::uint8_t c[4] = {std::uint8_t(dark ? 45 : 240), std::uint8_t(dark ? 85 : 240),
                                       std::uint8_t(dark ? 190 : 235), 255};
            for (int k = 0; k < 4; ++k) img.pixels[(std::size_t(y) * size + x) * 4 + k] = c[k];
        }
    return img;
}

}  // namespace

ChartsInputs read_charts_inputs(const std::string& mesh_path, const std::string& features_path, double snap,
                                const std::vector<NamedPath>& outputs) {
    ChartsInputs in;
    in.mesh = read_mesh(mesh_path);
    in.topology = compute_topology(in.mesh);
    require_manifold(in.topology, mesh_path);
    ChartFile file = read_chart_features(features_path);
    in.images = resolve_chart_images(file, in.sizes);
    std::vector<NamedPath> inputs{{mesh_path, "the mesh"}, {features_path, "the features file"}};
    for (std::size_t c = 0; c < in.images.size(); ++c)
        inputs.push_back({in.images[c], "the image of chart '" + file.charts[c].name + "'"});
    check_outputs(inputs, outputs);
    for (std::size_t c = 0; c < file.charts.size(); ++c) {
        const std::string& image = in.images[c];
        if (!image.empty() && exif_orientation(read_input_file(image, "image file")) != 1)
            throw BadInput(image,
                           "a JPEG turned by its EXIF orientation is not available as a chart's image yet: save it "
                           "upright (as PNG) first");
        naming_file(features_path, [&] { return check_features_on_mesh(file.charts[c].features, in.mesh, mesh_path, snap); });
    }
    for (std::size_t c = 0; c < file.charts.size(); ++c) {
        ChartInput ci;
        ci.name = file.charts[c].name;
        ci.features = map_features(file.charts[c].features, in.sizes[c][0], in.sizes[c][1]);
        ci.border = file.charts[c].border;
        in.charts.push_back(std::move(ci));
    }
    return in;
}

ChartsRun run_map_charts(const MapArgs& a) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    const std::string mtl = mtl_path_of(a);
    if (!a.image.empty())
        throw BadInput(a.features, "--image cannot be used with charts: each chart names its own \"image\"");
    if (a.copy_image)
        throw BadInput(a.features, "--copy-image is not available with charts yet: the MTL names each chart's image");
    check_outputs({{a.mesh, "the mesh"}, {a.features, "the features file"}},
                  {{a.output, "the output (-o)"}, {mtl, "the output's material file"}, {a.glb, "--glb"},
                   {a.report, "--report"}});
    ChartsInputs in = read_charts_inputs(a.mesh, a.features, a.snap,
                                         {{a.output, "the output (-o)"}, {mtl, "the output's material file"},
                                          {a.glb, "--glb"}, {a.report, "--report"}});
    const TriMesh& mesh = in.mesh;
    const std::vector<ChartInput>& charts = in.charts;
    ChartsRun run;
    run.images = in.images;
    run.sizes = in.sizes;
    if (!a.quiet) {
        std::cout << "ctmap map: " << a.mesh << " with " << charts.size() << (charts.size() == 1 ? " chart:" : " charts:");
        for (std::size_t c = 0; c < charts.size(); ++c)
            std::cout << (c ? ";" : "") << " " << quoted_name(charts[c].name) << " " << charts[c].features.size() << " features on "
                      << (run.images[c].empty() ? std::string("a") : terminal_text(run.images[c])) << " (" << run.sizes[c][0] << " x "
                      << run.sizes[c][1] << ")";
        std::cout << std::endl;
    }
    const double read_ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();

    MapOptions options = map_options(a);
    Progress progress(!a.quiet, isatty(fileno(stderr)));
    options.progress = [&](const std::string& stage, int done, int total) { progress(stage, done, total); };
    run.result = naming_file(a.features, [&] { return map_charts(mesh, charts, options); });
    progress.clear();
    run.result.timings_ms.read = read_ms;
    run.result.timings_ms.total += read_ms;

    // Everything to temporaries first, renamed together at the end.
    OutputSet outputs;
    std::vector<ChartMaterial> materials;
    for (std::size_t c = 0; c < charts.size(); ++c) materials.push_back({chart_material_name(charts[c].name), run.images[c]});
    // The faces in no chart: their own material, a checker written beside the OBJ.
    std::string rest_tmp;
    if (run.result.rest.faces > 0) {
        const std::string rest_png =
            (fs::path(a.output).parent_path() / (fs::path(a.output).stem().string() + "_rest.png")).string();
        check_outputs({{a.mesh, "the mesh"}, {a.features, "the features file"}}, {{rest_png, "the rest's checker"}});
        rest_tmp = outputs.add(rest_png);
        write_text_file(rest_tmp, encode_png(checker_image(512, 8)));
        materials.push_back({"rest", rest_png});
    }
    write_obj(run.result.textured, a.output, materials, outputs);
    run.written = {a.output, mtl};
    if (!rest_tmp.empty()) run.written.push_back(materials.back().image);
    if (!a.glb.empty()) {
        std::vector<ChartMaterial> embedded = materials;
        if (!rest_tmp.empty()) embedded.back().image = rest_tmp;  // not yet renamed into place
        write_glb(run.result.textured, a.glb, embedded, outputs);
        run.written.push_back(a.glb);
    }
    if (!a.report.empty()) {
        nlohmann::json j;
        const TexturedMesh& tm = run.result.textured;
        j["inputs"] = {{"mesh", a.mesh}, {"features", a.features}};
        j["counts"] = {{"charts", charts.size()},
                       {"input_vertices", mesh.num_vertices()},
                       {"input_faces", mesh.num_faces()},
                       {"vertices", tm.mesh.num_vertices()},
                       {"faces", tm.mesh.num_faces()},
                       {"seam_pieces", run.result.seams.size()},
                       {"seam_pieces_rerouted", run.result.seams_rerouted}};
        const MapTimings& t = run.result.timings_ms;
        j["timings_ms"] = {{"read", t.read},     {"triangulate", t.triangulate}, {"paths", t.paths},
                           {"embed", t.embed},   {"refine", t.refine},           {"optimise", t.optimise},
                           {"certify", t.certify}, {"total", t.total}};
        j["certificate"] = certificate_to_json(run.result.certificate);
        const RestMap& rest = run.result.rest;
        j["rest"] = {{"faces", rest.faces}, {"pieces", rest.pieces}, {"cut_edges", rest.cut_edges},
                     {"iterations", rest.iterations},
                     {"material", rest.faces > 0 ? nlohmann::json("rest") : nlohmann::json(nullptr)}};
        j["charts"] = nlohmann::json::array();
        for (std::size_t c = 0; c < charts.size(); ++c) {
            const ChartMap& cm = run.result.charts[c];
            MapReportInputs report_in{a.mesh, a.features, run.images[c], run.sizes[c][0], run.sizes[c][1],
                               int(cm.result.cut.num_input_vertices), 0};
            nlohmann::json chart = map_report(cm.result, report_in);
            chart["name"] = cm.name;
            chart["material"] = materials[c].name;
            chart["faces"] = cm.faces.size();
            j["charts"].push_back(chart);
        }
        const std::string tmp = outputs.add(a.report);
        write_text_file(tmp, j.dump(2) + "\n");
        run.written.push_back(a.report);
    }
    outputs.commit_all();
    return run;
}

void print_charts_summary(const MapArgs&, const ChartsRun& run, std::ostream& os) {
    const ChartsResult& r = run.result;
    const Certificate& c = r.certificate;
    for (const ChartMap& cm : r.charts) {
        const MapResult& m = cm.result;
        os << "  chart '" << cm.name << "': " << m.triangulation.triangles.size() << " patches, " << cm.faces.size()
           << " faces, certificate " << (m.certificate.valid ? "valid" : "INVALID") << ", symmetric Dirichlet "
           << fixed(m.before_refine.symmetric_dirichlet, 3) << " -> " << fixed(m.certificate.distortion.symmetric_dirichlet, 3)
           << (m.certificate.mirrored ? " (mirrored)" : "") << "\n";
    }
    if (r.rest.faces > 0)
        os << "  the rest: " << r.rest.faces << " faces in no chart, " << r.rest.pieces << " piece(s) cut into discs ("
           << r.rest.cut_edges << " edges cut), mapped automatically with material rest (a checker)\n";
    os << "  " << r.seams.size() << " seam pieces";
    os << rerouted_text(r.seams_rerouted);
    os << ", " << r.textured.mesh.num_vertices() << " vertices, "
       << r.textured.mesh.num_faces() << " faces\n"
       << "  certificate: " << (c.valid ? "valid" : "INVALID") << " (" << c.flipped << " flipped, " << c.degenerate
       << " degenerate, feature error " << c.feature_max_error << " over " << r.occurrences.size()
       << " feature occurrences, every chart's border " << (c.border_simple ? "simple" : "crossing") << ")\n";
    const MapTimings& t = r.timings_ms;
    os << "  ms (each stage summed over the charts, which run in parallel): read " << fixed(t.read, 1)
       << ", seams and paths " << fixed(t.paths, 1) << ", embed " << fixed(t.embed, 1)
       << ", refine " << fixed(t.refine, 1) << ", optimise " << fixed(t.optimise, 1) << ", certify " << fixed(t.certify, 1)
       << ", total " << fixed(t.total, 1) << "\n  wrote";
    for (const std::string& f : run.written) os << " " << f;
    os << "\n";
}

int validate_charts(const std::string& mesh_path, const std::string& features_path, const std::string& image_arg,
                    double snap, const std::string& border) {
    if (!image_arg.empty())
        throw BadInput(features_path, "--image cannot be used with charts: each chart names its own \"image\"");
    const ChartsInputs in = read_charts_inputs(mesh_path, features_path, snap);
    const MeshTopology& t = in.topology;
    MapOptions options;
    options.snap = snap;
    options.auto_border = border == "auto";
    options.refine = false;  // the checks are the cut's and the layout's; the bare embedding is certified
    options.refine_mode = RefineMode::paper;
    const ChartsResult r = naming_file(features_path, [&] { return map_charts(in.mesh, in.charts, options); });
    std::cout << "ok: " << mesh_path << " is an oriented manifold (" << t.vertices << " vertices, " << t.faces
              << " faces, " << t.border_loops << " border loop(s), Euler characteristic " << t.euler << "); "
              << in.charts.size() << (in.charts.size() == 1 ? " chart in " : " charts in ") << features_path << "\n";
    for (std::size_t c = 0; c < r.charts.size(); ++c) {
        const ChartMap& cm = r.charts[c];
        std::cout << "  chart " << quoted_name(cm.name) << ": " << in.charts[c].features.size() << " features on "
                  << (in.images[c].empty() ? std::string("a") : terminal_text(in.images[c])) << " (" << in.sizes[c][0] << " x "
                  << in.sizes[c][1] << "), " << cm.result.triangulation.triangles.size() << " patches, "
                  << cm.faces.size() << " faces\n";
        if (!cm.result.auto_border.vertex.empty())
            std::cout << "    border: `ctmap map` adds " << cm.result.auto_border.vertex.size() << " border feature(s) ("
                      << cm.result.auto_border.reason << ")\n";
    }
    if (r.rest.faces > 0)
        std::cout << "  the rest: " << r.rest.faces << " faces in no chart, mapped automatically (" << r.rest.pieces
                  << " piece(s))\n";
    std::cout << "  " << r.seams.size() << " seam pieces";
    std::cout << rerouted_text(r.seams_rerouted);
    std::cout << "\n";
    return kExitOk;
}

}  // namespace ctmap::cli

// `ctmap morph`: a feature-aligned morph of one mesh into another (paper §4, issue 14): a GLB
// whose mesh carries the target shape as a glTF morph target, OBJ frames and a picture strip.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "commands.h"
#include "ctmap/certify/certificate.h"
#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"
#include "ctmap/io/glb_io.h"
#include "ctmap/io/image.h"
#include "ctmap/io/map_report.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/output_paths.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/morph/morph_meshes.h"
#include "ctmap/morph/morph_quality.h"
#include "ctmap/render/render_map.h"

namespace ctmap::cli {
namespace {

namespace fs = std::filesystem;

struct MorphArgs {
    std::string source, target, pairs, output, obj_frames, strip, report, view = "front";
    int frames = 5;
    bool resample = true, align = true, quiet = false;
};

std::string frame_path(const std::string& dir, int k) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%03d.obj", k);
    return (fs::path(dir) / name).string();
}

/// The N frames side by side, each drawn with the domain's checker (the same square on both
/// shapes is the same part of the correspondence) and the pairs' markers.
Image render_strip(const MorphResult& m, int frames, RenderView view) {
    const int size = 384;
    Image strip;
    strip.width = size * frames;
    strip.height = size;
    strip.channels = 4;
    strip.pixels.assign(std::size_t(strip.width) * strip.height * 4, 255);
    for (int k = 0; k < frames; ++k) {
        TexturedMesh tm = TexturedMesh::with_vertex_uvs(m.common.mesh, m.common.uv);
        tm.mesh.positions = morph_frame(m.common, frames > 1 ? double(k) / (frames - 1) : 0.0);
        RenderScene scene;
        scene.mesh = &tm;
        scene.feature_vertex = m.pair_vertex;
        RenderOptions o;
        o.width = o.height = size;
        o.mode = RenderMode::checker;
        o.view = view;
        o.checker_cells = 16;
        const Image pic = render_map(scene, o);
        for (int y = 0; y < size; ++y)
            std::copy_n(&pic.pixels[std::size_t(y) * size * 4], size * 4,
                        &strip.pixels[(std::size_t(y) * strip.width + std::size_t(k) * size) * 4]);
    }
    return strip;
}

nlohmann::json stages(const MapTimings& t) {
    return {{"triangulate", t.triangulate}, {"paths", t.paths}, {"embed", t.embed}, {"refine", t.refine},
            {"optimise", t.optimise}, {"certify", t.certify}};
}

/// The `--report` JSON: inputs, counts, both certificates, the quality figures and the times.
nlohmann::json morph_report(const MorphArgs& a, const PairSet& pairs, const MorphResult& m, const MorphQuality& q) {
    const auto& t = m.timings_ms;
    return {
        {"inputs", {{"source", a.source}, {"target", a.target}, {"pairs", a.pairs}}},
        {"counts",
         {{"pairs", pairs.pairs.size()}, {"border_pairs", m.border_pairs}, {"vertices", m.common.mesh.num_vertices()},
          {"faces", m.common.mesh.num_faces()}, {"from_source", m.common.source_vertices},
          {"from_target", m.common.inserted}, {"shared", m.common.merged}, {"crossings", m.common.crossings}}},
        {"certificates", {{"target_map", certificate_to_json(m.target_map.certificate)},
                          {"source_map", certificate_to_json(m.source_map.certificate)}}},
        {"distortion", {{"target_map", distortion_json(m.target_map.certificate.distortion)},
                        {"source_map", distortion_json(m.source_map.certificate.distortion)}}},
        {"quality",
         {{"pair_error", q.pair_error}, {"off_target", q.target_off}, {"off_source", q.source_off},
          {"hausdorff_target_to_morph", q.hausdorff}, {"target_mean_edge", q.target_mean_edge},
          {"target_diagonal", q.diagonal}}},
        {"timings_ms", {{"target_map", t.target_map}, {"source_map", t.source_map}, {"common_mesh", t.common_mesh},
                        {"total", t.total}}},
        {"map_stages_ms", {{"target", stages(m.target_map.timings_ms)}, {"source", stages(m.source_map.timings_ms)}}},
    };
}

int run_morph(const MorphArgs& a) {
    std::vector<NamedPath> outputs{{a.output, "the morph (-o)"}, {a.strip, "--strip"}, {a.report, "--report"}};
    const RenderView view = parse_render_view(a.view);  // before any work
    std::vector<fs::path> made;  // folders this run creates, deepest first
    if (!a.obj_frames.empty()) {
        for (fs::path p = fs::absolute(a.obj_frames); !p.empty() && !fs::exists(p); p = p.parent_path()) made.push_back(p);
        std::error_code ec;
        fs::create_directories(a.obj_frames, ec);
        if (ec) throw BadInput(a.obj_frames, "cannot create the --obj-frames folder: " + ec.message());
        for (int k = 0; k < a.frames; ++k) {
            const std::string obj = frame_path(a.obj_frames, k);
            outputs.push_back({obj, "--obj-frames"});
            outputs.push_back({fs::path(obj).replace_extension(".mtl").string(), "--obj-frames"});
        }
    }
    try {
        check_outputs({{a.source, "the source mesh"}, {a.target, "the target mesh"}, {a.pairs, "the pairs file"}}, outputs);
        const TriMesh source = read_mesh(a.source), target = read_mesh(a.target);
        const PairSet pairs = read_pairs(a.pairs);
        MorphOptions options;
        options.resample = a.resample;
        options.align = a.align;
        if (!a.quiet) options.progress = [](const std::string& stage) { std::cerr << "ctmap morph: " << stage << "\n"; };
        const MorphResult m = morph_meshes(source, target, pairs, options, a.source, a.target);
        const MorphQuality q = measure_morph(m, target);

        OutputSet files;
        write_morph_glb(m.common.mesh, m.common.target_position, a.output, files);
        for (int k = 0; !a.obj_frames.empty() && k < a.frames; ++k) {
            TexturedMesh tm = TexturedMesh::with_vertex_uvs(m.common.mesh, m.common.uv);
            tm.mesh.positions = morph_frame(m.common, a.frames > 1 ? double(k) / (a.frames - 1) : 0.0);
            write_obj(tm, frame_path(a.obj_frames, k), "", files);
        }
        if (!a.strip.empty()) {
            const std::string png = encode_png(render_strip(m, a.frames, view));
            std::ofstream os(files.add(a.strip), std::ios::binary);
            os.write(png.data(), std::streamsize(png.size()));
            if (!os.flush()) throw InternalError(a.strip + ": could not write the strip");
        }
        if (!a.report.empty()) {
            std::ofstream os(files.add(a.report), std::ios::binary);
            os << morph_report(a, pairs, m, q).dump(2) << "\n";
            if (!os.flush()) throw InternalError(a.report + ": could not write the report");
        }
        files.commit_all();
        if (a.quiet) return kExitOk;
        const auto& t = m.timings_ms;
        std::cout << "morph " << a.source << " -> " << a.target << ": " << pairs.pairs.size() << " pairs ("
                  << m.border_pairs.size() << " on the borders)\n"
                  << "  common mesh: " << m.common.mesh.num_vertices() << " vertices (" << m.common.source_vertices
                  << " from the source's map, " << m.common.inserted << " from the target's, " << m.common.merged
                  << " shared, " << m.common.crossings << " edge crossings), " << m.common.mesh.num_faces() << " faces\n"
                  << "  maps: target " << (m.target_map.certificate.valid ? "certified" : "INVALID") << ", source "
                  << (m.source_map.certificate.valid ? "certified" : "INVALID")
                  << "; distortion (symmetric Dirichlet / 4, 1 = isometric): target map "
                  << m.target_map.certificate.distortion.symmetric_dirichlet / 4 << ", source map "
                  << m.source_map.certificate.distortion.symmetric_dirichlet / 4 << "\n"
                  << "  pairs on their target points: max error " << q.pair_error << " (" << q.pair_error / q.diagonal
                  << " of the target's diagonal)\n"
                  << "  morphed vertices off the target surface: max " << q.target_off << " (" << q.target_off / q.diagonal
                  << " of the diagonal); off the source: max " << q.source_off << "\n"
                  << "  Hausdorff distance target -> morphed surface: " << q.hausdorff << " (target's mean edge "
                  << q.target_mean_edge << ")\n"
                  << "  time: target map " << t.target_map / 1000 << " s, source map " << t.source_map / 1000
                  << " s, common mesh " << t.common_mesh / 1000 << " s, total " << t.total / 1000 << " s\n"
                  << "wrote " << a.output;
        if (!a.obj_frames.empty()) std::cout << ", " << a.frames << " OBJ frames in " << a.obj_frames;
        if (!a.strip.empty()) std::cout << ", " << a.strip;
        std::cout << "\n";
        return kExitOk;
    } catch (...) {
        std::error_code ec;
        for (const fs::path& p : made) fs::remove(p, ec);  // empty: no frame was committed
        throw;
    }
}

}  // namespace

Command add_morph_command(CLI::App& app) {
    auto a = std::make_shared<MorphArgs>();
    auto* sub = app.add_subcommand(
        "morph",
        "Morph one mesh into another with paired features aligned (paper §4): both share one mesh; writes a GLB "
        "with the target as a glTF morph target and an animation of its weight");
    sub->add_option("SOURCE", a->source, "source mesh (a topological disc: OFF/OBJ/PLY/STL)")->required();
    sub->add_option("TARGET", a->target, "target mesh (a topological disc)")->required();
    sub->add_option("PAIRS", a->pairs,
                    "pairs file (.json): {\"pairs\": [{\"name\", \"source\": {\"vertex\"|\"point\"}, \"target\": {...}}]}; "
                    "at least 3 pairs on both borders, in the same order along them")
        ->required();
    sub->add_option("-o,--output", a->output, "the morph as binary glTF (.glb): three.js and Blender play it")->required();
    sub->add_option("--frames", a->frames, "frames for --obj-frames and --strip (weights 0 to 1)")
        ->capture_default_str()
        ->check(CLI::Range(2, 200));
    sub->add_option("--obj-frames", a->obj_frames, "folder for OBJ frames frame_000.obj ... (made if missing)");
    sub->add_option("--strip", a->strip, "a PNG of the frames side by side, checker in the shared domain");
    sub->add_option("--report", a->report, "a JSON report: counts, both maps' certificates, distances, times");
    sub->add_option("--view", a->view, "camera side of --strip: front, side, back, top, three-quarter, left, bottom")->capture_default_str();
    sub->add_flag("!--no-resample", a->resample,
                  "no overlay: the source's connectivity only, the target surface sampled at its vertices");
    sub->add_flag("!--no-align", a->align,
                  "morph the source as it is placed (default: moved, turned and scaled onto the target's pairs first)");
    sub->add_flag("-q,--quiet", a->quiet, "print nothing on success");
    return {sub, [a] { return run_morph(*a); }};
}

}  // namespace ctmap::cli

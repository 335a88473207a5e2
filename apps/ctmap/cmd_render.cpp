// `ctmap render`: a picture of a texture map (issue 5) — textured, checker, UV layout, cut paths
// or feature triangulation — drawn off-screen by OpenGL and written as PNG.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>

#include "commands.h"
#include "ctmap/errors.h"
#include "ctmap/io/atomic_file.h"
#include "ctmap/io/output_paths.h"
#include "ctmap/render/render_inputs.h"
#include "ctmap/render/render_map.h"

namespace ctmap::cli {
namespace {

struct RenderArgs {
    RenderFiles files;
    std::string output;
    std::string view = "front";
    std::string mode = "textured";
    std::string size = "1024";
    std::string background = "white";
    bool flat = false;
    bool whole_image = false;
    bool quiet = false;
};

/// "W" (square for the 3D modes, the image's aspect for the image-plane ones) or "WxH".
void parse_size(const std::string& s, int& w, int& h) {
    auto bad = [&](const std::string& why) {
        return BadInput("--size", "'" + s + "': " + why + " (give W or WxH in pixels, each " +
                                      std::to_string(RenderOptions::kMinSize) + " to " +
                                      std::to_string(RenderOptions::kMaxSize) + ")");
    };
    auto number = [&](const std::string& t) {
        if (t.empty() || t.size() > 6 || t.find_first_not_of("0123456789") != std::string::npos)
            throw bad("not a whole number");
        return std::stoi(t);
    };
    const std::size_t x = s.find_first_of("xX");
    w = number(s.substr(0, x));
    h = x == std::string::npos ? 0 : number(s.substr(x + 1));
    auto ok = [](int v) { return v >= RenderOptions::kMinSize && v <= RenderOptions::kMaxSize; };
    if (!ok(w) || (h != 0 && !ok(h))) throw bad("out of range");
}

std::array<std::uint8_t, 4> parse_background(const std::string& s) {
    if (s == "white") return {255, 255, 255, 255};
    if (s == "black") return {0, 0, 0, 255};
    if (s == "transparent" || s == "none") return {0, 0, 0, 0};
    if (s.size() == 7 || s.size() == 9) {
        if (s[0] == '#' && s.find_first_not_of("0123456789abcdefABCDEF", 1) == std::string::npos) {
            std::array<std::uint8_t, 4> c{0, 0, 0, 255};
            for (std::size_t i = 1, k = 0; i + 1 < s.size(); i += 2, ++k)
                c[k] = std::uint8_t(std::stoi(s.substr(i, 2), nullptr, 16));
            return c;
        }
    }
    throw BadInput("--background", "'" + s + "' is not a colour (white, black, transparent, #rrggbb or #rrggbbaa)");
}

int run_render(const RenderArgs& a) {
    const auto start = std::chrono::steady_clock::now();
    RenderOptions opt;
    opt.mode = parse_render_mode(a.mode);
    opt.view = parse_render_view(a.view);
    int w = 0, h = 0;
    parse_size(a.size, w, h);
    opt.background = parse_background(a.background);
    opt.shading = !a.flat;
    if (a.output.size() < 4 || [&] {
            std::string e = a.output.substr(a.output.size() - 4);
            for (char& c : e) c = char(std::tolower((unsigned char)c));
            return e != ".png";
        }())
        throw BadInput(a.output, "the picture is written as PNG: name it *.png");
    // Before drawing: the picture overwrites no input, and its folder takes a new file.
    check_outputs({{a.files.map, "the map"}, {a.files.features, "the features file"}, {a.files.image, "the image"}},
                  {{a.output, "the picture (-o)"}});

    const RenderInputs in = read_render_inputs(a.files, {opt.mode});
    opt.width = w;
    opt.height = h != 0 ? h : w;
    opt.whole_image = a.whole_image;
    if (h == 0 && !is_3d(opt.mode)) {  // the shown region's aspect, so the picture has no empty bands
        const Eigen::AlignedBox2d r = image_plane_region(in.scene(), opt);
        const double ratio = r.sizes().y() / r.sizes().x();
        opt.height = std::clamp(int(std::lround(w * ratio)), RenderOptions::kMinSize, RenderOptions::kMaxSize);
    }
    const Image picture = render_map(in.scene(), opt);
    write_png(picture, a.output);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    char took[32];
    std::snprintf(took, sizeof took, "%.0f ms", ms);
    if (!a.quiet)
        std::cout << "wrote " << a.output << " (" << opt.width << " x " << opt.height << ", " << to_string(opt.mode)
              << (is_3d(opt.mode) ? ", " + to_string(opt.view) + " view" : std::string()) << ", "
              << in.mesh.mesh.num_faces() << " triangles"
              << (in.feature_vertex.empty() ? "" : ", " + std::to_string(in.feature_vertex.size()) + " features")
              << ") in " << took << "\n";
    return kExitOk;
}

}  // namespace

Command add_render_command(CLI::App& app) {
    auto args = std::make_shared<RenderArgs>();
    CLI::App* sub = app.add_subcommand(
        "render", "Draw a texture map as a PNG: textured, checker (distortion), uv (layout over the image), "
                  "paths (the cut on the mesh) or triangulation (features over the image)");
    sub->add_option("MAP", args->files.map, "textured OBJ or GLB (from `ctmap map`, or any OBJ with UVs)")->required();
    sub->add_option("-o,--output", args->output, "PNG file to write")->required();
    sub->add_option("--mode", args->mode, "textured | checker | uv | paths | triangulation")
        ->check(CLI::IsMember({"textured", "checker", "uv", "paths", "triangulation"}))
        ->capture_default_str();
    sub->add_option("--view", args->view, "camera side for the 3D modes: front (from +z) | side (+x) | back (-z) | top (+y) | three-quarter | left (-x) | bottom (-y)")
        ->check(CLI::IsMember({"front", "side", "back", "top", "three-quarter", "left", "bottom"}))
        ->capture_default_str();
    sub->add_option("--size", args->size,
                    "W or WxH pixels (W alone: square in 3D; for uv and triangulation, the shown region's aspect)")
        ->capture_default_str();
    sub->add_option("--background", args->background, "white | black | transparent | #rrggbb | #rrggbbaa")
        ->capture_default_str();
    sub->add_option("--features", args->files.features, "features.json: markers, and the triangulation (README, features.json)");
    sub->add_option("--image", args->files.image, "texture image; overrides the material's map_Kd");
    sub->add_option("--chart", args->files.chart,
                    "a map with several charts: draw only this chart (its name, or its material chart_<name>) with "
                    "its own image; without it, --mode textured draws every chart with its own image");
    sub->add_flag("--flat", args->flat, "no shading: the texture's own colours");
    sub->add_flag("--whole-image", args->whole_image, "uv, triangulation: the whole image, not just around the map");
    sub->add_flag("-q,--quiet", args->quiet, "print nothing on success");
    return {sub, [args] { return run_render(*args); }};
}

}  // namespace ctmap::cli

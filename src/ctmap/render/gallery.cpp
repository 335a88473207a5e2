// The demo gallery (gallery.h): five pictures and a static HTML page.
#include "ctmap/render/gallery.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "ctmap/errors.h"

namespace ctmap {
namespace {

std::string html_escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            default: out += c;
        }
    }
    return out;
}

struct ModeText {
    RenderMode mode;
    const char* figure;
    const char* title;
    const char* caption;
};

// In the order of the pipeline (paper §2.2-2.4), so the page reads as the method runs.
const ModeText kGalleryModes[] = {
    {RenderMode::triangulation, "Fig. 1c", "Feature triangulation",
     "The features' image points joined by a constrained Delaunay triangulation; dark: the border polygon "
     "(border features in the order the mesh border meets them), red: the inner edges, which become the cut "
     "paths. Each triangle becomes one patch of the mesh."},
    {RenderMode::paths, "Fig. 1d", "Cut paths on the mesh",
     "Approximate shortest paths (red) between the features cut the mesh into one patch per image triangle "
     "(each patch tinted; dark: the mesh border); the paths meet only at features and leave each feature in "
     "the triangulation's order."},
    {RenderMode::uv, "Fig. 1e/g", "UV layout over the image",
     "Every mesh triangle where it lands in the image (white), the cut paths (red), the mesh border (dark) and "
     "the features (dots): each feature exactly on its image point, no triangle flipped."},
    {RenderMode::checker, "Fig. 1i", "Checker (distortion)",
     "A checker in image space carried onto the mesh: squares that stay square and even show a low-distortion "
     "map; stretched or sheared squares show where the constraints pull."},
    {RenderMode::textured, "Fig. 5-7", "Textured",
     "The mesh shaded and textured with the image: the photograph's features sit on the matching parts of the "
     "surface."},
};

}  // namespace

std::vector<GalleryPicture> write_gallery(const RenderFiles& files, const std::string& out_dir, const std::string& stem,
                                          const GalleryOptions& options, OutputSet& outputs) {
    std::vector<RenderMode> modes;
    for (const ModeText& m : kGalleryModes)
        if (m.mode != RenderMode::triangulation || !files.features.empty()) modes.push_back(m.mode);
    const RenderInputs in = read_render_inputs(files, modes);
    const RenderScene scene = in.scene();
    const std::filesystem::path dir(out_dir);

    std::vector<GalleryPicture> pictures;
    for (const ModeText& m : kGalleryModes) {
        if (std::find(modes.begin(), modes.end(), m.mode) == modes.end()) continue;
        RenderOptions opt;
        opt.mode = m.mode;
        opt.view = options.view;
        opt.width = opt.height = options.size;
        if (!is_3d(m.mode)) {
            const Eigen::AlignedBox2d r = image_plane_region(scene, opt);
            opt.height = std::clamp(int(std::lround(options.size * r.sizes().y() / r.sizes().x())),
                                    RenderOptions::kMinSize, RenderOptions::kMaxSize);
        }
        const Image picture = render_map(scene, opt);
        GalleryPicture p{m.mode, stem + "_" + to_string(m.mode) + ".png", m.figure, m.caption};
        write_png(picture, outputs.add((dir / p.file).string()));
        pictures.push_back(p);
    }

    std::ostringstream html;
    html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << html_escape(options.title)
         << "</title>\n<style>\n"
         << "body{font-family:system-ui,sans-serif;margin:2em;background:#fafafa;color:#222}\n"
         << ".grid{display:grid;grid-template-columns:repeat(auto-fill,minmax(320px,1fr));gap:1.5em}\n"
         << "figure{margin:0;background:#fff;border:1px solid #ddd;padding:.8em}\n"
         << "figure img{width:100%;height:auto;display:block}\n"
         << "figcaption{font-size:.9em;line-height:1.4;margin-top:.5em}\n"
         << ".fig{font-weight:600;color:#a11}\n</style>\n</head>\n<body>\n"
         << "<h1>" << html_escape(options.title) << "</h1>\n";
    if (!options.notes.empty()) {
        html << "<ul>\n";
        for (const std::string& n : options.notes) html << "<li>" << html_escape(n) << "</li>\n";
        html << "</ul>\n";
    }
    html << "<p>Guo, Wang, Cui, Peng, <i>A New Constrained Texture Mapping Method</i>: each picture below redraws "
            "the figure of the paper named in its caption, for this map.</p>\n<div class=\"grid\">\n";
    for (const ModeText& m : kGalleryModes) {
        const auto it = std::find_if(pictures.begin(), pictures.end(), [&](const GalleryPicture& p) { return p.mode == m.mode; });
        html << "<figure>\n";
        if (it != pictures.end())
            html << "<img src=\"" << html_escape(it->file) << "\" alt=\"" << html_escape(m.title) << "\">\n";
        else
            html << "<p>(not drawn: no features file was given)</p>\n";
        html << "<figcaption><span class=\"fig\">" << m.figure << "</span> &mdash; <b>" << m.title << ".</b> "
             << html_escape(m.caption) << "</figcaption>\n</figure>\n";
    }
    html << "</div>\n<p>Drawn with <code>ctmap render MAP.obj -o OUT.png --mode MODE</code> (OpenGL off-screen: "
         << html_escape(render_backend()) << ").</p>\n</body>\n</html>\n";
    const std::string page = outputs.add((dir / "index.html").string());
    std::ofstream os(page, std::ios::binary);
    os << html.str();
    if (!os.flush()) throw InternalError((dir / "index.html").string() + ": could not write the page");
    return pictures;
}

}  // namespace ctmap

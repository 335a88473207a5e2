#pragma once
/// \file gallery.h
/// The demo's gallery (issue 5): the five pictures of one map and a page that shows them side by
/// side, each beside the figure of the paper it redraws, so a newcomer sees what ctmap did in one
/// look.
#include <string>
#include <vector>

#include "ctmap/io/atomic_file.h"
#include "ctmap/render/render_inputs.h"
#include "ctmap/render/render_map.h"

namespace ctmap {

/// Options of `write_gallery`.
struct GalleryOptions {
    std::string title = "ctmap";       ///< page title, e.g. "nefertiti on astronaut.png"
    std::vector<std::string> notes;    ///< lines shown under the title (certificate, timings, ...)
    int size = 768;                    ///< picture width in pixels (3D: square; image plane: the region's aspect)
    RenderView view = RenderView::front;
};

/// One written picture.
struct GalleryPicture {
    RenderMode mode;
    std::string file;  ///< file name inside the gallery folder
    std::string figure;  ///< the paper's figure it redraws, e.g. "Fig. 1c"
    std::string caption;
};

/// Draws the map of `files` in the five modes (triangulation, paths, uv, checker, textured: the
/// order of the pipeline) as `<stem>_<mode>.png` in `out_dir`, plus `index.html` that shows them,
/// all registered in `outputs` (they appear when the caller commits it). The triangulation
/// picture needs `files.features`; without it that picture is left out and the page says so.
/// \pre out_dir exists.
/// \throw BadInput as read_render_inputs (a map without UVs, patches or image);
///        InternalError if OpenGL fails.
std::vector<GalleryPicture> write_gallery(const RenderFiles& files, const std::string& out_dir, const std::string& stem,
                                          const GalleryOptions& options, OutputSet& outputs);

}  // namespace ctmap

// Reading and checking the inputs of a picture (render_inputs.h).
#include "ctmap/render/render_inputs.h"

#include <algorithm>
#include <filesystem>
#include <limits>

#include "ctmap/certify/certificate.h"
#include "ctmap/cut/cut_mesh.h"
#include "ctmap/domain/auto_border.h"
#include "ctmap/errors.h"
#include "ctmap/io/chart_features.h"
#include "ctmap/io/glb_io.h"
#include "ctmap/io/image.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/obj_io.h"

namespace ctmap {

RenderScene RenderInputs::scene() const {
    RenderScene s;
    s.mesh = &mesh;
    s.image = image ? &*image : nullptr;
    s.feature_vertex = feature_vertex;
    s.feature_uv = feature_uv;
    s.triangulation = triangulation ? &*triangulation : nullptr;
    for (const Image& img : chart_images) s.chart_images.push_back(&img);
    return s;
}

namespace {

bool any(const std::vector<RenderMode>& modes, std::initializer_list<RenderMode> of) {
    return std::any_of(modes.begin(), modes.end(),
                       [&](RenderMode m) { return std::find(of.begin(), of.end(), m) != of.end(); });
}

std::string mode_names(const std::vector<RenderMode>& modes, std::initializer_list<RenderMode> of) {
    std::string s;
    for (RenderMode m : modes)
        if (std::find(of.begin(), of.end(), m) != of.end()) s += (s.empty() ? "" : ", ") + to_string(m);
    return "--mode " + s;
}

}  // namespace

RenderInputs read_render_inputs(const RenderFiles& files, const std::vector<RenderMode>& modes) {
    using M = RenderMode;
    RenderInputs in;
    std::string mtl_image;
    std::string ext = std::filesystem::path(files.map).extension().string();
    for (char& c : ext) c = char(std::tolower((unsigned char)c));
    GlbTexture embedded;
    std::vector<ChartMaterial> materials;
    in.mesh = ext == ".glb" ? read_glb(files.map, &embedded) : read_textured_obj(files.map, &mtl_image, &materials);
    if (in.mesh.mesh.faces.empty()) throw BadInput(files.map, "no faces: nothing to draw");
    if (!files.chart.empty()) {
        // One chart: its faces only, with its material's image.
        int chart = -1;
        std::string names;
        for (std::size_t c = 0; c < materials.size(); ++c) {
            if (materials[c].name == files.chart || materials[c].name == chart_material_name(files.chart)) chart = int(c);
            names += (names.empty() ? "" : ", ") + materials[c].name;
        }
        if (chart < 0) throw BadInput(files.map, "no chart " + files.chart + " (its materials: " + names + ")");
        TexturedMesh one;
        one.mesh.positions = in.mesh.mesh.positions;
        one.uvs = in.mesh.uvs;
        for (std::size_t f = 0; f < in.mesh.mesh.faces.size(); ++f)
            if (in.mesh.chart[f] == chart) {
                one.mesh.faces.push_back(in.mesh.mesh.faces[f]);
                if (f < in.mesh.uv_faces.size()) one.uv_faces.push_back(in.mesh.uv_faces[f]);
                if (f < in.mesh.patch.size()) one.patch.push_back(in.mesh.patch[f]);
                one.chart.push_back(0);
            }
        in.mesh = std::move(one);
        mtl_image = materials[chart].image;
    } else if (materials.size() > 1 && files.image.empty() && any(modes, {RenderMode::textured}) &&
               std::all_of(materials.begin(), materials.end(), [](const ChartMaterial& m) { return !m.image.empty(); })) {
        // Several charts (ctmap's charts, or any OBJ whose materials each have an image): each
        // chart with its own image.
        for (const ChartMaterial& m : materials) in.chart_images.push_back(read_image(m.image));
    }
    if (in.chart_images.empty()) in.mesh.chart.assign(in.mesh.mesh.faces.size(), 0);  // one image for all
    const bool has_uv = !in.mesh.uvs.empty() && in.mesh.uv_faces.size() == in.mesh.mesh.faces.size();
    if (!has_uv && any(modes, {M::textured, M::checker, M::uv}))
        throw BadInput(files.map, "no texture coordinates (`vt` and `f v/vt`), which " +
                                      mode_names(modes, {M::textured, M::checker, M::uv}) +
                                      " needs: make a map first with `ctmap map`");
    if (in.mesh.patch.size() != in.mesh.mesh.faces.size() && any(modes, {M::paths}))
        throw BadInput(files.map, "no patch groups (`g patch_<id>` before the faces), which --mode paths needs to "
                                  "find the cut: use an OBJ written by `ctmap map`");

    if (!files.features.empty()) in.features = read_features(files.features);
    const bool needs_image = any(modes, {M::textured, M::uv, M::triangulation});
    std::string image = !files.image.empty() ? files.image : !mtl_image.empty() ? mtl_image : in.features.image;
    if (needs_image && image.empty() && embedded.bytes.empty())
        throw BadInput(files.map, "no texture image (its material has no `map_Kd`), which " +
                                      mode_names(modes, {M::textured, M::uv, M::triangulation}) +
                                      " needs: give --image");
    if (image.empty() && !embedded.bytes.empty() && needs_image) {  // a GLB's own texture
        in.image = decode_image(std::string(embedded.bytes.begin(), embedded.bytes.end()), files.map);
        in.image_path = files.map;
    } else if (!image.empty()) {
        if (needs_image || !files.image.empty() || std::filesystem::exists(image)) {
            // read_image names the file (the material's map_Kd, resolved against its folder) when
            // it is missing or broken.
            in.image = read_image(image);
            in.image_path = image;
        }
    }

    if (!files.features.empty()) {
        FeatureSet& fs = in.features;
        int w = 0, h = 0;
        if (in.image) w = in.image->width, h = in.image->height;
        else if (fs.image_size) w = (*fs.image_size)[0], h = (*fs.image_size)[1];
        else throw BadInput(files.features, "no image size for the features: give --image, or \"image\" or "
                                            "\"image_size\" in the features file");
        resolve_units(fs, w, h);
        check_features_on_mesh(fs, in.mesh.mesh, files.map);
        in.feature_vertex = feature_vertices_on_map(fs, in.mesh.mesh, files.map);
        for (const Feature& f : fs.features) in.feature_uv.push_back(image_to_uv(f.image, w, h));
    }

    if (any(modes, {M::triangulation})) {
        if (files.features.empty())
            throw BadInput(files.map, "--mode triangulation draws the features' triangulation: give --features");
        require_disc(compute_topology(in.mesh.mesh), files.map);
        std::vector<std::string> names;
        for (const Feature& f : in.features.features) names.push_back(f.name);
        // Where the features cannot make the paper's border, the border features `ctmap map
        // --border auto` places (fitted again on this mesh, so they can differ a little).
        const AutoBorder added = naming_file(files.features, [&] {
            return place_border_features(in.mesh.mesh, in.feature_vertex, in.feature_uv, names);
        });
        std::vector<int> fv = in.feature_vertex;
        std::vector<Vec2> uv = in.feature_uv;
        fv.insert(fv.end(), added.vertex.begin(), added.vertex.end());
        uv.insert(uv.end(), added.uv.begin(), added.uv.end());
        names.resize(fv.size());
        in.triangulation = naming_file(
            files.features, [&] { return triangulate_features(uv, border_features(in.mesh.mesh, fv), names); });
    }
    return in;
}

}  // namespace ctmap

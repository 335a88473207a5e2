// Input of the viewer test (issue 4 must-show 5): a texture that is a distinct solid colour blob
// at each of nefertiti's feature image points on a neutral grey background, and the features
// file that points at it (nefertiti's features, the same pixels). The test maps them, opens the
// GLB and the OBJ + MTL in three.js in headless Chromium and looks for each feature's blob colour
// where the feature vertex is drawn (tests/web/viewer_test.mjs).
//
// Usage: ctmap_viewer_fixture OUT_DIR [--map]
// Writes OUT_DIR/nefertiti.off (a copy of the mesh), OUT_DIR/blobs.png, OUT_DIR/features.json and
// OUT_DIR/expected.json (per feature: name, vertex, 3D position, image point, colour painted
// there). CTest then maps them with `ctmap map` (tests/CMakeLists.txt). With --map, the fixture
// makes the map itself through the library (map_texture, then write_obj and write_glb to
// OUT_DIR/map.obj, map.mtl, map.glb), to tell a viewer failure from a CLI one by hand.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "ctmap/errors.h"
#include "ctmap/io/data_path.h"
#include "ctmap/io/features.h"
#include "ctmap/io/glb_io.h"
#include "ctmap/io/image.h"
#include "ctmap/io/obj_io.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"

namespace {

/// Blob radius in texture pixels. Where two blobs would overlap, a pixel takes the colour of the
/// nearest feature, so every feature's own point always carries its own colour.
constexpr double kRadius = 12;
const std::array<int, 3> kBackground{128, 128, 128};

/// n saturated colours, hues spread evenly and every other one darker, far from the grey background.
std::vector<std::array<int, 3>> palette(int n) {
    std::vector<std::array<int, 3>> out;
    for (int i = 0; i < n; ++i) {
        const double h = 6.0 * i / n, v = i % 2 ? 150.0 : 255.0;
        const double x = 1 - std::abs(std::fmod(h, 2.0) - 1);
        std::array<double, 3> rgb{};
        switch (int(h)) {
            case 0: rgb = {1, x, 0}; break;
            case 1: rgb = {x, 1, 0}; break;
            case 2: rgb = {0, 1, x}; break;
            case 3: rgb = {0, x, 1}; break;
            case 4: rgb = {x, 0, 1}; break;
            default: rgb = {1, 0, x}; break;
        }
        out.push_back({int(std::lround(v * rgb[0])), int(std::lround(v * rgb[1])), int(std::lround(v * rgb[2]))});
    }
    return out;
}

int max_channel_difference(const std::array<int, 3>& a, const std::array<int, 3>& b) {
    return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
}

}  // namespace

int main(int argc, char** argv) {
    const bool map = argc == 3 && std::string(argv[2]) == "--map";
    if (argc != 2 && !map) {
        std::cerr << "usage: ctmap_viewer_fixture OUT_DIR [--map]\n";
        return 2;
    }
    try {
        const std::filesystem::path out = argv[1];
        std::filesystem::create_directories(out);
        const std::string mesh_file = ctmap::find_data_file("meshes/nefertiti.off");
        std::filesystem::copy_file(mesh_file, out / "nefertiti.off", std::filesystem::copy_options::overwrite_existing);
        ctmap::FeatureSet fs = ctmap::read_features(ctmap::find_data_file("features/nefertiti_astronaut.json"));
        // Only the photo's size is used (the same pixels). It is looked up like the other data,
        // since the features file may sit in the project's data/ without the images.
        const ctmap::Image photo = ctmap::read_image(ctmap::find_data_file("images/astronaut.png"));
        ctmap::resolve_units(fs, photo.width, photo.height);
        const int n = int(fs.features.size());
        const ctmap::TriMesh mesh = ctmap::read_mesh(mesh_file);
        ctmap::check_features_on_mesh(fs, mesh, mesh_file);
        const std::vector<std::array<int, 3>> colours = palette(n);
        // The viewer test matches within 8 levels per channel; colours must stay far apart from
        // each other and from the background for a match to name one feature.
        int closest = 255;
        for (int i = 0; i < n; ++i) {
            closest = std::min(closest, max_channel_difference(colours[i], kBackground));
            for (int j = 0; j < i; ++j) closest = std::min(closest, max_channel_difference(colours[i], colours[j]));
        }
        if (closest < 48) throw ctmap::InternalError("palette colours too close: " + std::to_string(closest));

        ctmap::Image tex;
        tex.width = photo.width;
        tex.height = photo.height;
        tex.channels = 4;
        tex.pixels.assign(std::size_t(tex.width) * tex.height * 4, 255);
        for (int y = 0; y < tex.height; ++y)
            for (int x = 0; x < tex.width; ++x) {
                // Pixel (x, y) covers [x, x+1) x [y, y+1): its centre is what a sampler reads.
                const ctmap::Vec2 c(x + 0.5, y + 0.5);
                int best = -1;
                double best_d = kRadius;
                for (int i = 0; i < n; ++i) {
                    const double d = (fs.features[i].image - c).norm();
                    if (d <= best_d) best = i, best_d = d;
                }
                const std::array<int, 3>& rgb = best < 0 ? kBackground : colours[best];
                for (int k = 0; k < 3; ++k) tex.pixels[(std::size_t(y) * tex.width + x) * 4 + k] = std::uint8_t(rgb[k]);
            }
        ctmap::write_png(tex, (out / "blobs.png").string());

        ctmap::FeatureSet blobs = fs;
        blobs.image = "blobs.png";  // resolved against the features file's folder
        std::ofstream(out / "features.json") << ctmap::features_to_json(blobs);

        nlohmann::json expected = nlohmann::json::array();
        for (int i = 0; i < n; ++i) {
            const ctmap::Feature& f = fs.features[i];
            const ctmap::Vec3 p = f.vertex >= 0 ? mesh.positions[f.vertex] : *f.point;
            expected.push_back({{"name", f.name},
                                {"vertex", f.vertex},
                                {"position", {p.x(), p.y(), p.z()}},
                                {"image", {f.image.x(), f.image.y()}},
                                {"colour", colours[i]}});
        }
        std::ofstream(out / "expected.json") << nlohmann::json{{"image_size", {tex.width, tex.height}},
                                                               {"radius_px", kRadius},
                                                               {"background", kBackground},
                                                               {"features", expected}}
                                                    .dump(2);
        if (map) {
            const ctmap::MapResult r = ctmap::map_texture(mesh, ctmap::map_features(fs, tex.width, tex.height));
            ctmap::write_obj(r.textured(), (out / "map.obj").string(), (out / "blobs.png").string());
            ctmap::write_glb(r.textured(), (out / "map.glb").string(), (out / "blobs.png").string());
        }
        std::cout << "viewer fixture: " << n << " feature blobs in " << (out / "blobs.png").string() << " ("
                  << tex.width << "x" << tex.height << "), closest colours differ by " << closest << " levels\n";
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "ctmap_viewer_fixture: " << e.what() << "\n";
        return 3;
    }
}

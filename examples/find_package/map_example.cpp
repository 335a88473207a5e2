// Maps a mesh with a features file through the installed ctmap library and prints what the
// certificate says: the smallest program a user of find_package(ctmap) writes.
#include <ctmap/errors.h>
#include <ctmap/io/features.h>
#include <ctmap/io/mesh_topology.h>
#include <ctmap/io/read_mesh.h>
#include <ctmap/map_texture.h>

#include <iostream>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::cerr << "usage: map_example MESH FEATURES.json\n";
        return 2;
    }
    try {
        const ctmap::TriMesh mesh = ctmap::read_mesh(argv[1]);
        ctmap::require_disc(ctmap::compute_topology(mesh), argv[1]);
        ctmap::FeatureSet fs = ctmap::read_features(argv[2]);
        int w = 0, h = 0;
        ctmap::resolve_feature_image(fs, "", w, h);
        // map_texture names no file in its messages; naming_file adds the features file's name.
        const ctmap::MapResult r =
            ctmap::naming_file(argv[2], [&] { return ctmap::map_texture(mesh, ctmap::map_features(fs, w, h)); });
        std::cout << "map of " << argv[1] << ": " << r.certificate.triangles << " triangles, "
                  << (r.certificate.valid ? "valid" : "INVALID") << ", " << r.certificate.flipped << " flipped\n";
        return r.certificate.valid ? 0 : 1;
    } catch (const ctmap::BadInput& e) {
        std::cerr << "bad input: " << e.what() << "\n";
        return 2;
    }
}

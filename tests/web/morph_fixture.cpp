// Input of the morph browser test (issue 14 must-show 3): copies the shipped example pair
// (nefertiti -> lion-head and its pairs file) into OUT_DIR, where CTest runs the real `ctmap morph`
// and `ctmap convert` on them and tests/web/morph_test.mjs opens the results in three.js.
//
// Usage: ctmap_morph_fixture OUT_DIR
#include <filesystem>
#include <iostream>

#include "ctmap/errors.h"
#include "ctmap/io/data_path.h"

int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: ctmap_morph_fixture OUT_DIR\n";
        return 2;
    }
    namespace fs = std::filesystem;
    try {
        const fs::path dir(argv[1]);
        fs::create_directories(dir);
        for (const char* f : {"meshes/nefertiti.off", "meshes/lion-head.off", "pairs/nefertiti_lion-head.json"})
            fs::copy_file(ctmap::find_data_file(f), dir / fs::path(f).filename(), fs::copy_options::overwrite_existing);
        for (const char* f : {"morph.glb", "source.glb", "target.glb"}) fs::remove(dir / f);  // no stale result
    } catch (const std::exception& e) {
        std::cerr << "ctmap_morph_fixture: " << e.what() << "\n";
        return 1;
    }
    return 0;
}

#include "ctmap/input_faces.h"

#include <tbb/parallel_for.h>

#include "ctmap/surface_locator.h"

namespace ctmap {

std::vector<int> input_faces_of(const TriMesh& input, const TriMesh& refined) {
    const SurfaceLocator locator(input);
    std::vector<int> out(refined.faces.size(), -1);
    tbb::parallel_for(std::size_t(0), out.size(), [&](std::size_t f) {
        const Tri& t = refined.faces[f];
        const Vec3 c = (refined.positions[t[0]] + refined.positions[t[1]] + refined.positions[t[2]]) / 3.0;
        out[f] = locator.closest(c).face;
    });
    return out;
}

}  // namespace ctmap

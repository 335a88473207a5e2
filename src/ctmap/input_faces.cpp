#include "ctmap/input_faces.h"

#include <tbb/parallel_for.h>


#include "ctmap/surface_locator.h"
#include "ctmap/unit_box.h"

namespace ctmap {

std::vector<int> input_faces_of(const TriMesh& input, const TriMesh& refined) {
    // In the input's unit box: a mesh in tiny or huge units keeps its faces' areas away from
    // underflow and overflow (the map does not depend on the unit).
    const UnitBox box = UnitBox::of(input);
    auto unit = [&](const Vec3& p) { return box.in(p); };
    TriMesh scaled = input;
    for (Vec3& p : scaled.positions) p = unit(p);
    const SurfaceLocator locator(scaled);
    std::vector<int> out(refined.faces.size(), -1);
    tbb::parallel_for(std::size_t(0), out.size(), [&](std::size_t f) {
        const Tri& t = refined.faces[f];
        const Vec3 c = (unit(refined.positions[t[0]]) + unit(refined.positions[t[1]]) + unit(refined.positions[t[2]])) / 3.0;
        out[f] = locator.closest(c).face;
    });
    return out;
}

}  // namespace ctmap

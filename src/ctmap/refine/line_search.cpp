#include "ctmap/refine/line_search.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <limits>

#include "ctmap/certify/certificate.h"
#include "ctmap/refine/flip_free_step.h"

namespace ctmap {

LineSearchResult flip_free_line_search(const IsometricProblem& p, const std::vector<FaceFrame>& frames,
                                       const Scaffold* scaffold,
                                       const BorderGuard& guard, bool check_border,
                                       const std::vector<Vec2>& uv, const std::vector<Vec2>& d, double e0,
                                       std::vector<Vec2>& trial) {
    LineSearchResult r;
    r.scaffold_bound = scaffold ? scaffold->max_step(uv, d) : std::numeric_limits<double>::infinity();
    r.bound = std::min(max_flip_free_step(p.tris, uv, d, p.sigma, p.parallel), r.scaffold_bound);
    const int na = int(p.tris.size());
    double step = std::min(1.0, 0.9 * r.bound);
    for (int h = 0; h < 60 && step > 0; ++h, step *= 0.5) {
        if (h > 0) ++r.halvings;
        r.step = step;
        for (int v = 0; v < p.nv; ++v) trial[v] = p.dof[v].n == 0 ? uv[v] : Vec2(uv[v] + step * d[v]);
        const double sd = p.energy(frames, trial);
        const double e1 = sd + p.barrier->value(trial) + (scaffold ? scaffold->energy(trial) : 0.0);
        if (!(e1 < e0)) continue;
        std::atomic<bool> exact{true};
        auto check = [&](int i) {
            if (!exact.load(std::memory_order_relaxed)) return;
            const Tri& t = p.tris[i];
            if (orientation_2d(trial[t[0]], trial[t[1]], trial[t[2]]) != p.sigma) exact = false;
        };
        if (p.parallel) tbb::parallel_for(0, na, check);
        else for (int i = 0; i < na; ++i) check(i);
        if (exact && scaffold && !scaffold->exact_ok(trial)) exact = false;
        if (!exact) {
            ++r.exact_rejections;
            continue;
        }
        if (check_border ? !guard.ok(trial) : !guard.inside(trial)) {
            ++r.border_rejections;
            continue;
        }
        r.accepted = true;
        r.energy = sd;
        r.objective = e1;
        break;
    }
    return r;
}

}  // namespace ctmap

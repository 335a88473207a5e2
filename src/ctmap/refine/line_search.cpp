#include "ctmap/refine/line_search.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>

#include "ctmap/certify/certificate.h"
#include "ctmap/refine/flip_free_step.h"

namespace ctmap {

LineSearchResult flip_free_line_search(const IsometricProblem& p, const std::vector<FaceFrame>& frames,
                                       const BorderGuard& guard, bool check_border, const std::vector<Vec2>& uv,
                                       std::vector<Vec2>& d, double e0, std::vector<Vec2>& trial) {
    LineSearchResult r;
    const int na = int(p.tris.size());
    auto start = [&] { return std::min(1.0, 0.9 * max_flip_free_step(p.tris, uv, d, p.sigma, p.parallel)); };
    double step = start();
    int holds = 0;
    for (int h = 0; h < 60 && step > 0; ++h, step *= 0.5) {
        if (h > 0) ++r.halvings;
        r.step = step;
        for (int v = 0; v < p.nv; ++v) trial[v] = p.dof[v].n == 0 ? uv[v] : Vec2(uv[v] + step * d[v]);
        const double sd = p.energy(frames, trial);
        const double e1 = sd + p.barrier->value(trial);
        if (!(e1 < e0)) continue;
        std::atomic<bool> exact{true};
        auto check = [&](int i) {
            if (!exact.load(std::memory_order_relaxed)) return;
            const Tri& t = p.tris[i];
            if (orientation_2d(trial[t[0]], trial[t[1]], trial[t[2]]) != p.sigma) exact = false;
        };
        if (p.parallel) tbb::parallel_for(0, na, check);
        else for (int i = 0; i < na; ++i) check(i);
        if (!exact) {
            ++r.exact_rejections;
            continue;
        }
        if (check_border ? !guard.ok(trial) : !guard.inside(trial)) {
            ++r.border_rejections;
            if (check_border && holds < 8 && guard.inside(trial)) {
                bool held = false;
                for (int v : guard.crossing_vertices(trial))
                    if (d[v] != Vec2::Zero()) d[v] = Vec2::Zero(), held = true, r.held.push_back(v);
                if (held) {
                    ++holds;
                    ++r.holds;
                    step = 2 * start();
                    h = -1;  // the loop's step halving and ++h bring it back to the new start
                }
            }
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

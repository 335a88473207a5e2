#pragma once
// Random feasible two-chart sets on closed meshes (issue 13, must-show 4): a seam loop of
// features round the mesh's middle cuts it into two discs; each disc is mapped one-to-one
// (Tutte's map, twisted) and features are picked on both, so a valid map of both charts exists.
#include <random>
#include <string>

#include "ctmap/border_loop.h"
#include "ctmap/cut/chart_regions.h"
#include "ctmap/domain/bisection_seam.h"
#include "ctmap/map_charts.h"
#include "random_features.h"

namespace ctmap::test {

struct TwoChartCase {
    std::vector<ChartInput> charts;
    std::vector<int> seam;  ///< the seam features' vertices
};

/// `seam_count` seam features round the middle, `interior` features per chart (fewer where the
/// twisted disc has no room clear of the border), chart image points from each half's Tutte map
/// twisted by `strength`; the second chart mirrored if `mirror_second`.
inline TwoChartCase two_chart_case(const TriMesh& mesh, int seam_count, int interior, double strength, std::mt19937& rng,
                                   bool mirror_second = false) {
    TwoChartCase out;
    out.seam = bisection_seam_vertices(mesh, seam_count);
    // The two sides of the seam, as map_charts will find them (no interior features yet: the
    // side on the left of the loop for a counter-clockwise chart, on the right for the other).
    std::vector<ChartOutline> outlines(2);
    for (int c = 0; c < 2; ++c) {
        outlines[c].name = c == 0 ? "front" : "back";
        outlines[c].border = out.seam;
        for (std::size_t i = 0; i < out.seam.size(); ++i) outlines[c].border_names.push_back("seam" + std::to_string(i));
        outlines[c].image_ccw = c == 0;
    }
    const ChartRegions regions = chart_regions(mesh, outlines);
    for (int c = 0; c < 2; ++c) {
        const ChartRegion& r = regions.charts[c];
        // Tutte's map squeezes a leg or an ear into a sliver of the disc; spread by area, the
        // image points ask for a map of moderate distortion, as a photo would.
        const std::vector<Vec2> tutte = spread_radially(r.mesh, tutte_map(r.mesh));
        std::vector<int> local(mesh.num_vertices(), -1);
        for (std::size_t v = 0; v < r.global.size(); ++v) local[r.global[v]] = int(v);
        // Border features: the seam; interior ones at random, kept inside the border polygon.
        const bool mirror = c == 1 && mirror_second;
        auto image = [&](int v) {
            Vec2 p = twist(tutte[v], strength);
            if (mirror) p.x() = -p.x();
            return Vec2(0.5 + 0.45 * p.x(), 0.5 + 0.45 * p.y());
        };
        ChartInput ch;
        ch.name = outlines[c].name;
        std::vector<Vec2> polygon;
        for (std::size_t i = 0; i < out.seam.size(); ++i) {
            MapFeature f;
            f.name = outlines[c].border_names[i];
            f.vertex = out.seam[i];
            f.uv = image(local[out.seam[i]]);
            polygon.push_back(f.uv);
            ch.features.push_back(f);
            ch.border.push_back(f.name);
        }
        std::vector<char> on_border(r.mesh.num_vertices(), 0);
        for (int v : border_loop(r.mesh)) on_border[v] = 1;
        std::vector<int> candidates;
        for (int v = 0; v < r.mesh.num_vertices(); ++v)
            if (!on_border[v]) candidates.push_back(v);
        std::shuffle(candidates.begin(), candidates.end(), rng);
        int added = 0;
        for (int v : candidates) {
            if (added >= interior) break;
            const Vec2 q = image(v);
            if (!clear_inside(polygon, q)) continue;  // the input rule for interior features
            MapFeature f;
            f.name = ch.name + "_" + std::to_string(added++);
            f.vertex = r.global[v];
            f.uv = q;
            ch.features.push_back(f);
        }
        out.charts.push_back(std::move(ch));
    }
    return out;
}

}  // namespace ctmap::test

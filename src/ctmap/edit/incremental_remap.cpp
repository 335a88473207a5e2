#include "ctmap/edit/incremental_remap.h"

#include <algorithm>
#include <chrono>
#include <limits>

#include "ctmap/errors.h"
#include "ctmap/refine/bump_move.h"

namespace ctmap {
namespace {

/// Each UV's distance to the segment [a, b].
std::vector<double> distances_to_segment(const std::vector<Vec2>& uv, const Vec2& a, const Vec2& b) {
    std::vector<double> out(uv.size());
    const Vec2 ab = b - a;
    const double len2 = ab.squaredNorm();
    for (std::size_t i = 0; i < uv.size(); ++i) {
        const double t = len2 > 0 ? std::clamp((uv[i] - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
        out[i] = (uv[i] - (a + t * ab)).norm();
    }
    return out;
}

/// The vertices whose UV lies within `reach` of the segment [a, b].
std::vector<int> vertices_near(const std::vector<Vec2>& uv, const Vec2& a, const Vec2& b, double reach) {
    const std::vector<double> dist = distances_to_segment(uv, a, b);
    std::vector<int> out;
    for (int i = 0; i < int(uv.size()); ++i)
        if (dist[i] <= reach) out.push_back(i);
    return out;
}

}  // namespace

std::optional<MapResult> remap_moved_feature(const MapResult& previous, int feature, const Vec2& target,
                                             const MapOptions& options, std::string* why, const RemapOptions& remap) {
    using Clock = std::chrono::steady_clock;
    const auto t0 = Clock::now();
    auto no = [&](const char* reason) {
        if (why) *why = reason;
        return std::optional<MapResult>();
    };
    if (!options.refine || options.refine_mode != RefineMode::isometric) return no("no optimiser in the options");
    if (feature < 0 || feature >= int(previous.cut.feature_vertex.size())) return no("no such feature");
    if (!(remap.region_vertices > 0 && remap.radius > 0 && remap.region >= 1 && remap.local_reach >= 0))
        throw BadInput("", "RemapOptions: region_vertices and radius must be positive, region at least 1, "
                           "local_reach not negative");
    MapResult r = previous;
    std::vector<int> fixed = r.cut.feature_vertex;
    if (r.auto_border_fixed) fixed.insert(fixed.end(), r.auto_border.vertex.begin(), r.auto_border.vertex.end());
    // The optimiser's rectangle, as map_texture chose it: the image, widened to hold the map.
    IsometricOptions iopt = options.isometric;
    for (const Vec2& p : r.uv) iopt.box_lo = iopt.box_lo.cwiseMin(p), iopt.box_hi = iopt.box_hi.cwiseMax(p);
    iopt.box_lo = iopt.box_lo.cwiseMin(target), iopt.box_hi = iopt.box_hi.cwiseMax(target);
    iopt.scale = previous.isometric_stats.scale;  // the same energy as the map it continues
    iopt.on_iteration = nullptr;
    const int v = r.cut.feature_vertex[feature];
    // The feature goes as far towards the target as a bump gives a valid start (all the way, else
    // half, a quarter of the rest); the map is optimised there with the feature held, which
    // evens out the triangles the bump squeezed, and the rest of the move starts from that.
    bool moved_any = false;
    double radius = std::numeric_limits<double>::infinity();
    Vec2 map_lo = r.uv[v], map_hi = r.uv[v];
    for (const Vec2& p : r.uv) map_lo = map_lo.cwiseMin(p), map_hi = map_hi.cwiseMax(p);
    const bool local = remap.local && (target - r.uv[v]).norm() <= remap.local_reach * (map_hi - map_lo).norm();
    if (local) {
        // At most `region_vertices` vertices within `region` radii of the move's path (the map's
        // density varies a lot: a radius alone can take in most of it), but never a bump that
        // needs more than a few steps.
        radius = remap.radius * (map_hi - map_lo).norm();
        std::vector<double> dist = distances_to_segment(r.uv, r.uv[v], target);
        if (remap.region_vertices < int(dist.size())) {
            std::nth_element(dist.begin(), dist.begin() + remap.region_vertices, dist.end());
            radius = std::min(radius, dist[remap.region_vertices] / remap.region);
        }
        radius = std::max(radius, 4 * (target - r.uv[v]).norm() / 3.1);
    }
    for (int stage = 0; stage < 4 && r.uv[v] != target; ++stage) {
        const Vec2 from = r.uv[v];
        bool started = false;
        for (double t : {1.0, 0.5, 0.25}) {
            std::vector<Vec2> trial = r.uv;
            const Vec2 to = t == 1.0 ? target : Vec2(from + t * (target - from));
            if (!bump_move(trial, v, to, fixed, iopt.box_lo, iopt.box_hi, 8, radius)) continue;
            if (local) iopt.movable = vertices_near(r.uv, from, to, remap.region * radius);
            try {
                IsometricStats st = optimise_isometric(r.cut.mesh, trial, fixed, iopt);
                r.isometric_stats = std::move(st);
            } catch (const BadInput&) {  // the bumped start folds a triangle or crosses the border
                continue;
            } catch (const InternalError&) {  // a solver failed: the whole pipeline decides
                return no("the optimiser failed from the bumped map");
            }
            r.uv = std::move(trial);
            started = moved_any = true;
            break;
        }
        if (!started) return no(moved_any ? "the rest of the move gives no valid start" : "no bump gives a valid start");
    }
    if (r.uv[v] != target) return no("the move needs more than four stages");
    r.feature_uv[feature] = target;
    const auto t1 = Clock::now();
    r.certificate = certify(r.textured(), r.cut.feature_vertex, r.feature_uv);
    if (!r.certificate.valid) return no("the certificate failed");
    r.timings_ms = MapTimings{};
    r.timings_ms.optimise = std::chrono::duration<double, std::milli>(t1 - t0).count();
    r.timings_ms.certify = std::chrono::duration<double, std::milli>(Clock::now() - t1).count();
    r.timings_ms.total = r.timings_ms.optimise + r.timings_ms.certify;
    return r;
}

}  // namespace ctmap

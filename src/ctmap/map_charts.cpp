#include "ctmap/map_charts.h"

#include <algorithm>
#include <chrono>
#include <map>
#include <set>

#include "ctmap/border_loop.h"
#include "ctmap/errors.h"
#include "ctmap/io/mesh_topology.h"

namespace ctmap {
namespace {

std::string named(const std::string& s) { return "'" + s + "'"; }

double signed_area(const std::vector<Vec2>& polygon) {
    double a = 0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const Vec2 &p = polygon[i], &q = polygon[(i + 1) % polygon.size()];
        a += p.x() * q.y() - q.x() * p.y();
    }
    return a / 2;
}

/// Runs `f()`; a BadInput it throws is thrown again with the chart named first.
template <class F>
decltype(auto) naming_chart(const std::string& chart, F&& f) {
    try {
        return f();
    } catch (const TopologyError& e) {
        throw TopologyError(e.file(), "chart " + named(chart) + ": " + e.problem());
    } catch (const BadInput& e) {
        throw BadInput(e.file(), "chart " + named(chart) + ": " + e.problem());
    }
}

void add_timings(MapTimings& sum, const MapTimings& t) {
    sum.triangulate += t.triangulate, sum.paths += t.paths, sum.embed += t.embed, sum.refine += t.refine;
    sum.optimise += t.optimise, sum.certify += t.certify;
}

}  // namespace

std::vector<int> ChartsResult::occurrence_vertices() const {
    std::vector<int> v;
    for (const FeatureOccurrence& o : occurrences) v.push_back(o.vertex);
    return v;
}
std::vector<Vec2> ChartsResult::occurrence_uvs() const {
    std::vector<Vec2> v;
    for (const FeatureOccurrence& o : occurrences) v.push_back(o.uv);
    return v;
}
std::vector<int> ChartsResult::occurrence_charts() const {
    std::vector<int> v;
    for (const FeatureOccurrence& o : occurrences) v.push_back(o.chart);
    return v;
}

ChartsResult map_charts(const TriMesh& input, const std::vector<ChartInput>& charts, const MapOptions& options) {
    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    if (charts.empty()) throw BadInput("", "no charts: give at least one");
    require_manifold(compute_topology(input), "");

    // Every feature once, by name: one place on the mesh in every chart.
    std::vector<MapFeature> unique;
    std::map<std::string, int> index_of;
    for (const ChartInput& c : charts)
        for (const MapFeature& f : c.features) {
            const auto [it, fresh] = index_of.emplace(f.name, int(unique.size()));
            if (fresh) {
                unique.push_back(f);
                continue;
            }
            const MapFeature& g = unique[it->second];
            if (g.vertex != f.vertex || (f.vertex < 0 && g.point != f.point))
                throw BadInput("", "feature " + named(f.name) + " is at another place on the mesh in chart " + named(c.name) +
                                       " than in an earlier chart: a feature is one place in every chart");
        }
    TriMesh mesh = input;
    const std::vector<int> vertex_of = place_point_features(mesh, unique, options.snap);

    ChartsResult out;
    if (charts.size() == 1 && charts[0].border.empty()) {
        // Today's single chart, bounded by the mesh border.
        ChartMap cm;
        cm.name = charts[0].name;
        cm.result = map_texture(input, charts[0].features, options);
        out.textured = cm.result.textured();
        for (int v = 0; v < cm.result.cut.mesh.num_vertices(); ++v) cm.vertex.push_back(v);
        for (int f = 0; f < cm.result.cut.mesh.num_faces(); ++f) cm.faces.push_back(f);
        for (std::size_t i = 0; i < charts[0].features.size(); ++i)
            out.occurrences.push_back({charts[0].features[i].name, 0, cm.result.cut.feature_vertex[i], cm.result.feature_uv[i]});
        out.certificate = cm.result.certificate;
        out.timings_ms = cm.result.timings_ms;
        out.charts.push_back(std::move(cm));
        return out;
    }

    // The seams, and each chart's region.
    std::vector<ChartOutline> outlines;
    for (const ChartInput& c : charts) {
        if (c.border.empty())
            throw BadInput("", "chart " + named(c.name) + " has no border: only a lone chart may be bounded by the mesh border");
        ChartOutline o;
        o.name = c.name;
        std::map<std::string, const MapFeature*> by_name;
        for (const MapFeature& f : c.features) by_name[f.name] = &f;
        std::vector<Vec2> polygon;
        for (const std::string& n : c.border) {
            const auto it = by_name.find(n);
            if (it == by_name.end())
                throw BadInput("", "chart " + named(c.name) + ": border feature " + named(n) + " is not one of its features");
            o.border.push_back(vertex_of[index_of.at(n)]);
            o.border_names.push_back(n);
            polygon.push_back(it->second->uv);
        }
        const std::set<std::string> on_border(c.border.begin(), c.border.end());
        for (const MapFeature& f : c.features)
            if (!on_border.count(f.name)) o.interior.push_back(vertex_of[index_of.at(f.name)]), o.interior_names.push_back(f.name);
        o.image_ccw = signed_area(polygon) > 0;
        outlines.push_back(std::move(o));
    }
    auto t0 = Clock::now();
    const ChartRegions regions = chart_regions(mesh, outlines);
    out.timings_ms.paths += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    const int in_no_chart = int(std::count(regions.face_chart.begin(), regions.face_chart.end(), -1));
    if (in_no_chart > 0)
        throw BadInput("", std::to_string(in_no_chart) + " of the mesh's " + std::to_string(mesh.num_faces()) +
                               " faces lie in no chart; the automatic map of the rest is not built yet (issue 13): "
                               "give charts that cover the mesh");

    // Each chart through the single-chart pipeline, on its region.
    out.textured.mesh.positions = mesh.positions;
    int patch_offset = 0;
    for (std::size_t c = 0; c < charts.size(); ++c) {
        const ChartRegion& region = regions.charts[c];
        std::vector<int> local(mesh.num_vertices(), -1);
        for (std::size_t v = 0; v < region.global.size(); ++v) local[region.global[v]] = int(v);
        std::vector<MapFeature> features;
        for (const MapFeature& f : charts[c].features) {
            MapFeature g = f;
            g.vertex = local[vertex_of[index_of.at(f.name)]];
            features.push_back(g);
        }
        ChartMap cm;
        cm.name = charts[c].name;
        cm.result = naming_chart(charts[c].name, [&] { return map_texture(region.mesh, features, options); });
        const MapResult& r = cm.result;
        // The region's vertices are the mesh's; what the chart's cut inserted is new, and must not
        // lie on the seam (the other chart would not have it).
        const int region_vertices = region.mesh.num_vertices();
        for (int v = 0; v < r.cut.mesh.num_vertices(); ++v) {
            if (v < region_vertices) {
                cm.vertex.push_back(region.global[v]);
                continue;
            }
            cm.vertex.push_back(out.textured.mesh.num_vertices());
            out.textured.mesh.positions.push_back(r.cut.mesh.positions[v]);
        }
        for (int v : border_loop(r.cut.mesh))
            if (v >= region_vertices)
                throw InternalError("chart " + named(charts[c].name) + ": the cut inserted a vertex on the seam");
        const int uv_offset = int(out.textured.uvs.size());
        out.textured.uvs.insert(out.textured.uvs.end(), r.uv.begin(), r.uv.end());
        int patches = 0;
        for (int f = 0; f < r.cut.mesh.num_faces(); ++f) {
            const Tri& t = r.cut.mesh.faces[f];
            cm.faces.push_back(out.textured.mesh.num_faces());
            out.textured.mesh.faces.push_back({cm.vertex[t[0]], cm.vertex[t[1]], cm.vertex[t[2]]});
            out.textured.uv_faces.push_back({t[0] + uv_offset, t[1] + uv_offset, t[2] + uv_offset});
            out.textured.chart.push_back(int(c));
            out.textured.patch.push_back(patch_offset + r.cut.face_patch[f]);
            patches = std::max(patches, r.cut.face_patch[f] + 1);
        }
        patch_offset += patches;
        for (std::size_t i = 0; i < features.size(); ++i)
            out.occurrences.push_back({features[i].name, int(c), cm.vertex[r.cut.feature_vertex[i]], r.feature_uv[i]});
        add_timings(out.timings_ms, r.timings_ms);
        out.charts.push_back(std::move(cm));
    }
    for (const std::vector<int>& s : regions.seams) out.seams.push_back(s);  // seam vertices keep their indices

    t0 = Clock::now();
    CertifyOptions copt;
    copt.feature_chart = out.occurrence_charts();
    out.certificate = certify(out.textured, out.occurrence_vertices(), out.occurrence_uvs(), copt);
    out.timings_ms.certify += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    out.timings_ms.total = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
    if (!out.certificate.valid)
        throw InternalError("the charts' map failed its certificate (" + std::to_string(out.certificate.flipped) +
                            " flipped, " + std::to_string(out.certificate.degenerate) + " degenerate, feature error " +
                            std::to_string(out.certificate.feature_max_error) + ", border " +
                            (out.certificate.border_simple ? "simple" : "not simple") + "); nothing was written");
    return out;
}

}  // namespace ctmap

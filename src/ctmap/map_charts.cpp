#include "ctmap/map_charts.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <chrono>
#include <exception>
#include <map>
#include <mutex>
#include <set>

#include <tbb/parallel_for.h>

#include "ctmap/border_loop.h"
#include "ctmap/cut/cut_to_disc.h"
#include "ctmap/domain/starter_features.h"
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

/// Maps the faces of `mesh` whose `face_chart` is -1 as chart `rest_chart` of `out`: each
/// connected piece cut open into a disc (cut/cut_to_disc.h), mapped onto a circle by Tutte's
/// convex combination map (one-to-one), optimised (refine/isometric.h, free border) and placed in
/// its own tile of the unit square. Appends the faces, their UVs, chart ids and patches (one per
/// piece, from `patch_base`) to `out`.
RestMap map_rest(const TriMesh& mesh, const std::vector<int>& face_chart, int rest_chart, int patch_base,
                 const MapOptions& options, TexturedMesh& out) {
    RestMap rest;
    const int nf = mesh.num_faces();
    // Pieces: rest faces joined through shared edges.
    std::map<std::pair<int, int>, std::vector<int>> faces_of_edge;
    for (int f = 0; f < nf; ++f)
        if (face_chart[f] < 0)
            for (int k = 0; k < 3; ++k)
                faces_of_edge[std::minmax(mesh.faces[f][k], mesh.faces[f][(k + 1) % 3])].push_back(f);
    std::vector<int> piece(nf, -1);
    std::vector<std::vector<int>> pieces;
    for (int f0 = 0; f0 < nf; ++f0) {
        if (face_chart[f0] >= 0 || piece[f0] >= 0) continue;
        pieces.emplace_back();
        std::vector<int> stack{f0};
        piece[f0] = int(pieces.size()) - 1;
        while (!stack.empty()) {
            const int f = stack.back();
            stack.pop_back();
            pieces.back().push_back(f);
            for (int k = 0; k < 3; ++k)
                for (int g : faces_of_edge[std::minmax(mesh.faces[f][k], mesh.faces[f][(k + 1) % 3])])
                    if (piece[g] < 0) piece[g] = piece[f0], stack.push_back(g);
        }
    }
    const int grid = int(std::ceil(std::sqrt(double(pieces.size()))));
    for (std::size_t p = 0; p < pieces.size(); ++p) {
        std::sort(pieces[p].begin(), pieces[p].end());
        TriMesh sub;
        std::vector<int> local(mesh.num_vertices(), -1), global;
        for (int f : pieces[p]) {
            Tri t;
            for (int k = 0; k < 3; ++k) {
                int& l = local[mesh.faces[f][k]];
                if (l < 0) l = sub.num_vertices(), global.push_back(mesh.faces[f][k]), sub.positions.push_back(mesh.positions[mesh.faces[f][k]]);
                t[k] = l;
            }
            sub.faces.push_back(t);
        }
        const DiscCut cut = cut_to_disc(sub);
        rest.cut_edges += cut.cut_edges;
        // Tutte's map onto the circle of this piece's tile, then the optimiser inside the tile.
        const double cell = 1.0 / grid;
        const Vec2 lo(cell * double(p % grid), 1.0 - cell * double(p / grid + 1));
        std::vector<Vec2> uv = tutte_map(cut.disc);
        for (Vec2& q : uv) q = lo + Vec2::Constant(0.5 * cell) + 0.45 * cell * q;
        if (options.refine && options.refine_mode == RefineMode::isometric) {
            IsometricOptions iopt = options.isometric;
            iopt.box_lo = lo, iopt.box_hi = lo + Vec2::Constant(cell);
            iopt.keep_in_box = true;
            iopt.border = BorderMode::free;
            iopt.on_iteration = nullptr;
            const IsometricStats st = optimise_isometric(cut.disc, uv, {}, iopt);
            rest.iterations += st.iterations;
        }
        const int uv_offset = int(out.uvs.size());
        out.uvs.insert(out.uvs.end(), uv.begin(), uv.end());
        for (std::size_t f = 0; f < cut.disc.faces.size(); ++f) {  // the piece's faces, in its order (cut_to_disc.h)
            const Tri& t = cut.disc.faces[f];
            out.mesh.faces.push_back({global[cut.original[t[0]]], global[cut.original[t[1]]], global[cut.original[t[2]]]});
            out.input_face.push_back(pieces[p][f]);
            out.uv_faces.push_back({t[0] + uv_offset, t[1] + uv_offset, t[2] + uv_offset});
            out.chart.push_back(rest_chart);
            out.patch.push_back(patch_base + int(p));  // a patch (OBJ group) per piece
        }
        rest.faces += cut.disc.num_faces();
    }
    rest.pieces = int(pieces.size());
    return rest;
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
    std::map<int, std::string> name_at;
    for (std::size_t i = 0; i < unique.size(); ++i) {
        const auto [it, fresh] = name_at.emplace(vertex_of[i], unique[i].name);
        if (!fresh)
            throw BadInput("", "features " + named(it->second) + " and " + named(unique[i].name) +
                                   " are at the same mesh vertex " + std::to_string(vertex_of[i]) +
                                   " (in different charts, a feature keeps one name)");
    }

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

    // Each chart through the single-chart pipeline, on its region. The charts run in parallel
    // (each chart's stages are parallel inside too) and are put together below in chart order;
    // the first chart in that order that fails is the one reported, so the output and the
    // messages do not depend on the threads.
    const std::size_t nc = charts.size();
    std::vector<std::vector<MapFeature>> chart_features(nc);
    std::vector<MapResult> results(nc);
    std::vector<std::exception_ptr> failure(nc);
    MapOptions inner = options;
    inner.progress = nullptr;  // one line for the charts: their stages would interleave
    std::mutex progress_mutex;
    int charts_done = 0;
    std::atomic<std::size_t> first_failed{nc};  // a chart after it need not run: its error is reported
    if (options.progress) options.progress("charts", 0, int(nc));
    tbb::parallel_for(std::size_t(0), nc, [&](std::size_t c) {
        if (first_failed.load() < c) return;
        try {
            const ChartRegion& region = regions.charts[c];
            std::vector<int> local(mesh.num_vertices(), -1);
            for (std::size_t v = 0; v < region.global.size(); ++v) local[region.global[v]] = int(v);
            for (const MapFeature& f : charts[c].features) {
                MapFeature g = f;
                g.vertex = local[vertex_of[index_of.at(f.name)]];
                chart_features[c].push_back(g);
            }
            results[c] = naming_chart(charts[c].name, [&] { return map_texture(region.mesh, chart_features[c], inner); });
            if (options.progress) {
                const std::lock_guard<std::mutex> lock(progress_mutex);
                options.progress("charts", ++charts_done, int(nc));
            }
        } catch (...) {
            failure[c] = std::current_exception();
            for (std::size_t f = first_failed.load(); c < f && !first_failed.compare_exchange_weak(f, c);) {
            }
        }
    });

    out.textured.mesh.positions = mesh.positions;
    int patch_offset = 0;
    for (std::size_t c = 0; c < nc; ++c) {
        // A chart's own failure before any check of its result below: the first in chart order.
        if (failure[c]) std::rethrow_exception(failure[c]);
        const ChartRegion& region = regions.charts[c];
        const std::vector<MapFeature>& features = chart_features[c];
        ChartMap cm;
        cm.name = charts[c].name;
        cm.result = std::move(results[c]);
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
            out.textured.input_face.push_back(region.faces[r.input_face[f]]);  // the region's face, then the mesh's
            patches = std::max(patches, r.cut.face_patch[f] + 1);
        }
        patch_offset += patches;
        for (std::size_t i = 0; i < features.size(); ++i)
            out.occurrences.push_back({features[i].name, int(c), cm.vertex[r.cut.feature_vertex[i]], r.feature_uv[i]});
        add_timings(out.timings_ms, r.timings_ms);
        out.charts.push_back(std::move(cm));
    }
    for (const std::vector<int>& s : regions.seams) out.seams.push_back(s);  // seam vertices keep their indices
    out.seams_rerouted = regions.rerouted;
    // The faces in no chart: mapped automatically as chart `charts.size()` ("rest").
    t0 = Clock::now();
    if (options.progress) options.progress("the rest", 0, 0);
    out.rest = map_rest(mesh, regions.face_chart, int(charts.size()), patch_offset, options, out.textured);
    out.timings_ms.optimise += std::chrono::duration<double, std::milli>(Clock::now() - t0).count();

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

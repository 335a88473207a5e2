// Stage times of the mapping (issue 3, must-show 4; paper Table 2): map_texture on lion-head and
// mannequin-devil with random feasible features (tests/random_features.h: mesh vertices through a
// Tutte map and a twist, so a valid cut exists), 10, 50 and 200 of them. The row's time is the whole
// pipeline; the counters split it into stages (MapResult::timings_ms, ms per run) and report the
// cut's size. BM_cut_paths compares the approximate paths with exact geodesics on one case.
#include <benchmark/benchmark.h>

#include <map>
#include <random>

#include "ctmap/cut/cut_mesh.h"
#include "ctmap/domain/feature_triangulation.h"
#include "ctmap/io/data_path.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "random_features.h"

namespace {

struct Case {
    ctmap::TriMesh mesh;
    std::vector<ctmap::MapFeature> features;
};

/// The same features on every run: a fixed seed per (mesh, count), 3 + count/4 of them (at most 40)
/// on the border, a moderate twist of one radian.
const Case& make_case(const std::string& name, int count) {
    static std::map<std::pair<std::string, int>, Case> cache;
    auto it = cache.find({name, count});
    if (it != cache.end()) return it->second;
    Case c;
    c.mesh = ctmap::read_mesh(ctmap::find_data_file("meshes/" + name));
    std::mt19937 rng(1000 + count);
    const auto rf = ctmap::test::random_features(c.mesh, ctmap::test::tutte_map(c.mesh), count,
                                                 std::min(40, 3 + count / 4), 1.0, rng);
    c.features = ctmap::test::map_features_of(rf);
    return cache.emplace(std::make_pair(name, count), std::move(c)).first->second;
}

void BM_map_stages(benchmark::State& state, const char* name) {
    const Case& c = make_case(name, int(state.range(0)));
    ctmap::MapTimings sum;
    ctmap::MapResult r;
    for (auto _ : state) {
        r = ctmap::map_texture(c.mesh, c.features);
        sum.triangulate += r.timings_ms.triangulate;
        sum.paths += r.timings_ms.paths;
        sum.embed += r.timings_ms.embed;
        sum.refine += r.timings_ms.refine;
        sum.certify += r.timings_ms.certify;
    }
    using benchmark::Counter;
    const auto avg = Counter::kAvgIterations;
    state.counters["features"] = double(c.features.size());
    state.counters["triangulate_ms"] = Counter(sum.triangulate, avg);
    state.counters["paths_ms"] = Counter(sum.paths, avg);
    state.counters["embed_ms"] = Counter(sum.embed, avg);
    state.counters["refine_ms"] = Counter(sum.refine, avg);
    state.counters["certify_ms"] = Counter(sum.certify, avg);
    state.counters["faces_in"] = c.mesh.num_faces();
    state.counters["faces_out"] = r.cut.mesh.num_faces();
    state.counters["inserted_v"] = r.cut_stats.inserted_vertices;
    state.counters["fallback"] = r.cut_stats.fallback_fired;
    state.counters["steiner_v"] = r.cut_stats.steiner_vertices;
}

/// The cut alone (triangulation given), approximate (arg 0) or exact geodesics (arg 1).
void BM_cut_paths(benchmark::State& state, const char* name, int count) {
    const Case& c = make_case(name, count);
    std::vector<int> fv;
    std::vector<ctmap::Vec2> uv;
    std::vector<std::string> names;
    for (const auto& f : c.features) {
        fv.push_back(f.vertex);
        uv.push_back(f.uv);
        names.push_back(f.name);
    }
    const auto ft = ctmap::triangulate_features(uv, ctmap::border_features(c.mesh, fv), names);
    ctmap::CutOptions opt;
    opt.exact_geodesics = state.range(0) == 1;
    ctmap::CutStats stats;
    for (auto _ : state) benchmark::DoNotOptimize(ctmap::cut_mesh(c.mesh, fv, ft, opt, &stats));
    state.counters["features"] = double(c.features.size());
    state.counters["paths"] = stats.paths;
    state.counters["exact_paths"] = stats.exact_paths;
    state.counters["exact_rejected"] = stats.exact_rejected;
    state.counters["length"] = stats.path_length;
    state.counters["inserted_v"] = stats.inserted_vertices;
}

}  // namespace

BENCHMARK_CAPTURE(BM_map_stages, lion_head, "lion-head.off")->Arg(10)->Arg(50)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_map_stages, mannequin_devil, "mannequin-devil.off")
    ->Arg(10)->Arg(50)->Arg(200)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_cut_paths, lion_head_50, "lion-head.off", 50)->ArgName("exact")->Arg(0)->Arg(1)
    ->Unit(benchmark::kMillisecond);

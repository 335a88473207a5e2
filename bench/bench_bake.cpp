// `ctmap bake` (issue 42 must-show 5): lion-head (16,674 triangles) mapped with its shipped
// features (lion-head_chelsea.json, chelsea.png), baked onto the mesh itself with a layout of its
// own (Tutte's, one to one), at 512² to 4096² texels: the exact transfer (each texel a barycentric point of its
// input face) and, for contrast, the closest-point transfer (CGAL's AABB tree) as for another
// tessellation. One run is one bake_texture call (rasterise, transfer, sample, pad); reading and
// writing files are not included. Texels per second in the counters show the scaling.
#include <benchmark/benchmark.h>

#include <cstdlib>

#include "ctmap/bake/bake_texture.h"
#include "ctmap/domain/starter_features.h"
#include "ctmap/io/data_path.h"
#include "ctmap/io/features.h"
#include "ctmap/io/image.h"
#include "ctmap/input_faces.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/subdivide.h"
#include "ctmap/map_texture.h"

namespace {

struct BakeScene {
    ctmap::TexturedMesh map, onto;
    ctmap::Image photo;
};

const BakeScene& bake_scene() {
    static const BakeScene s = [] {
        BakeScene x;
        const ctmap::TriMesh mesh = ctmap::read_mesh(ctmap::find_data_file("meshes/lion-head.off"));
        x.photo = ctmap::read_image(ctmap::find_data_file("images/chelsea.png"));
        ctmap::FeatureSet fs = ctmap::read_features(ctmap::find_data_file("features/lion-head_chelsea.json"));
        ctmap::resolve_units(fs, x.photo.width, x.photo.height);
        x.map = ctmap::map_texture(mesh, ctmap::map_features(fs, x.photo.width, x.photo.height)).textured();
        // ONTO: the input with a layout of its own, one to one (Tutte's, the unit disc into [0.02, 0.98]²).
        std::vector<ctmap::Vec2> uv = ctmap::tutte_map(mesh);
        for (ctmap::Vec2& q : uv) q = ctmap::Vec2(0.5, 0.5) + 0.48 * q;
        x.onto = ctmap::TexturedMesh::with_vertex_uvs(mesh, uv);
        return x;
    }();
    return s;
}

void BM_bake(benchmark::State& state, ctmap::BakeTransfer transfer) {
    const BakeScene& s = bake_scene();
    ctmap::BakeOptions opt;
    opt.width = opt.height = int(state.range(0));
    opt.transfer = transfer;
    if (const char* p = std::getenv("CTMAP_BAKE_PADDING")) opt.padding = std::atoi(p);
    ctmap::BakeStats stats;
    for (auto _ : state) {
        ctmap::BakeResult r = ctmap::bake_texture(s.map, {s.photo}, s.onto, opt);
        stats = r.stats;
        benchmark::DoNotOptimize(r.texture.pixels.data());
    }
    state.counters["covered_texels"] = double(stats.covered);
    state.counters["texels_per_s"] = benchmark::Counter(double(stats.covered), benchmark::Counter::kIsIterationInvariantRate);
    state.counters["exact"] = stats.exact ? 1 : 0;
}

BENCHMARK_CAPTURE(BM_bake, exact, ctmap::BakeTransfer::automatic)
    ->Arg(512)->Arg(1024)->Arg(2048)->Arg(4096)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_bake, closest, ctmap::BakeTransfer::closest)
    ->Arg(512)->Arg(1024)->Arg(2048)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

namespace {

/// The map's provenance (input_faces.h): what map_texture now spends at its end, per face of the
/// map. Measured on lion-head refined 1-to-4 `range(0)` times as the "map" (the cut refines less:
/// lion-head's map has 18,638 faces for 16,674 input faces), so the cost per refined face shows.
void BM_input_faces(benchmark::State& state) {
    const ctmap::TriMesh mesh = ctmap::read_mesh(ctmap::find_data_file("meshes/lion-head.off"));
    const ctmap::TriMesh refined = ctmap::subdivide_midpoint(mesh, int(state.range(0)));
    for (auto _ : state) benchmark::DoNotOptimize(ctmap::input_faces_of(mesh, refined).data());
    state.counters["refined_faces"] = double(refined.num_faces());
    state.counters["faces_per_s"] = benchmark::Counter(double(refined.num_faces()), benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_input_faces)->Arg(0)->Arg(1)->Arg(2)->Arg(3)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

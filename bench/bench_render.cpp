// Rendering (issue 5, must-show 3): a picture of a ~26k-triangle map at 1024 x 1024. The map is
// mannequin-devil (25,888 triangles) mapped with 12 random feasible features
// (tests/random_features.h), textured with astronaut.png. A run is one render_map call: vertex
// buffers built and uploaded, texture uploaded and mipmapped, drawn with 4x multisampling, the
// picture read back. The off-screen context is made once per process (its cost is reported by
// BM_render_first_context); writing the PNG is not included (BM_write_png).
#include <benchmark/benchmark.h>

#include <chrono>
#include <random>

#include "../tests/random_features.h"
#include "ctmap/io/data_path.h"
#include "ctmap/io/image.h"
#include "ctmap/io/read_mesh.h"
#include "ctmap/map_texture.h"
#include "ctmap/render/render_map.h"

namespace {

struct Scene {
    ctmap::TexturedMesh map;
    ctmap::Image image;
    std::vector<int> feature_vertex;
    std::vector<ctmap::Vec2> feature_uv;
    ctmap::FeatureTriangulation triangulation;
};

const Scene& scene() {
    static const Scene s = [] {
        Scene x;
        const ctmap::TriMesh mesh = ctmap::read_mesh(ctmap::find_data_file("meshes/mannequin-devil.off"));
        std::mt19937 rng(5);
        const auto rf = ctmap::test::random_features(mesh, ctmap::test::tutte_map(mesh), 12, 6, 1.0, rng);
        const std::vector<ctmap::MapFeature> features = ctmap::test::map_features_of(rf);
        const ctmap::MapResult r = ctmap::map_texture(mesh, features);
        x.map = r.textured();
        x.feature_vertex = r.cut.feature_vertex;
        x.feature_uv = r.feature_uv;
        x.triangulation = r.triangulation;
        x.image = ctmap::read_image(ctmap::find_data_file("images/astronaut.png"));
        return x;
    }();
    return s;
}

ctmap::RenderScene render_scene() {
    const Scene& s = scene();
    ctmap::RenderScene r;
    r.mesh = &s.map;
    r.image = &s.image;
    r.feature_vertex = s.feature_vertex;
    r.feature_uv = s.feature_uv;
    r.triangulation = &s.triangulation;
    return r;
}

void BM_render(benchmark::State& state, ctmap::RenderMode mode) {
    const ctmap::RenderScene rs = render_scene();
    ctmap::RenderOptions opt;
    opt.width = opt.height = int(state.range(0));
    opt.mode = mode;
    opt.view = ctmap::RenderView::three_quarter;
    benchmark::DoNotOptimize(ctmap::render_map(rs, opt));  // warm: shaders compiled for this state
    for (auto _ : state) benchmark::DoNotOptimize(ctmap::render_map(rs, opt));
    state.counters["triangles"] = rs.mesh->mesh.num_faces();
    state.SetLabel(ctmap::render_backend());
}

/// The first picture of a process: the EGL context, shader compilation and llvmpipe's code
/// generation for the draw state, as `ctmap render` pays once. One iteration only.
void BM_render_first_context(benchmark::State& state) {
    const ctmap::RenderScene rs = render_scene();
    ctmap::RenderOptions opt;
    opt.view = ctmap::RenderView::three_quarter;
    for (auto _ : state) benchmark::DoNotOptimize(ctmap::render_map(rs, opt));
    state.counters["triangles"] = rs.mesh->mesh.num_faces();
}

void BM_write_png(benchmark::State& state) {
    const ctmap::RenderScene rs = render_scene();
    ctmap::RenderOptions opt;
    const ctmap::Image img = ctmap::render_map(rs, opt);
    const std::string path = "/tmp/ctmap_bench_render.png";
    for (auto _ : state) ctmap::write_png(img, path);
    std::remove(path.c_str());
}

}  // namespace

// First, so it really is the first picture of the process.
BENCHMARK(BM_render_first_context)->Iterations(1)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_render, textured, ctmap::RenderMode::textured)->Arg(1024)->Arg(2048)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_render, checker, ctmap::RenderMode::checker)->Arg(1024)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_render, paths, ctmap::RenderMode::paths)->Arg(1024)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_render, uv, ctmap::RenderMode::uv)->Arg(1024)->UseRealTime()->Unit(benchmark::kMillisecond);
BENCHMARK(BM_write_png)->UseRealTime()->Unit(benchmark::kMillisecond);

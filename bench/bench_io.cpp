// Reading and topology on the real meshes: the fixed cost before any mapping (paper Table 2 does
// not count it; `ctmap map` reports it as timings_ms.read).
#include <benchmark/benchmark.h>

#include "ctmap/io/data_path.h"
#include "ctmap/io/mesh_topology.h"
#include "ctmap/io/read_mesh.h"

namespace {

void BM_read_mesh(benchmark::State& state, const char* name) {
    const std::string path = ctmap::find_data_file(std::string("meshes/") + name);
    for (auto _ : state) benchmark::DoNotOptimize(ctmap::read_mesh(path));
}

void BM_topology(benchmark::State& state, const char* name) {
    const ctmap::TriMesh mesh = ctmap::read_mesh(ctmap::find_data_file(std::string("meshes/") + name));
    for (auto _ : state) benchmark::DoNotOptimize(ctmap::compute_topology(mesh));
    state.counters["faces"] = mesh.num_faces();
}

}  // namespace

BENCHMARK_CAPTURE(BM_read_mesh, nefertiti, "nefertiti.off")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_read_mesh, mannequin_devil, "mannequin-devil.off")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_topology, nefertiti, "nefertiti.off")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_topology, mannequin_devil, "mannequin-devil.off")->Unit(benchmark::kMillisecond);

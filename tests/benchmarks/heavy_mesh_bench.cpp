// What scales with the triangle count, on the CPU: the shadow BVH's build,
// its memory per triangle, and the time per shadow ray (ShadowBvh::occluded)
// against the furnished room's. Scenes: make_heavy_room_scene (the furnished
// room and a sphere of N triangles); rays: from random floor points to
// random points under the ceiling, one fixed seed.
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

#include "editor_client/scene/heavy_mesh.h"
#include "editor_client/scene/scene_generator.h"
#include "lightcuts/occlusion/shadow_bvh.h"

namespace {

struct Ray {
    glm::dvec3 origin;
    glm::dvec3 direction;
};

std::vector<Ray> room_rays(size_t count) {
    std::mt19937_64 rng(20261127u);
    std::uniform_real_distribution<double> x(-4.9, 4.9);
    std::vector<Ray> rays(count);
    for (Ray& r : rays) {
        r.origin = {x(rng), 0.01, x(rng)};
        r.direction = glm::dvec3(x(rng), 2.9, x(rng)) - r.origin;
    }
    return rays;
}

lc::Scene scene_of(int64_t triangles) {
    if (triangles == 0) return lc::client::make_furnished_room_scene();
    return lc::client::make_heavy_room_scene(uint32_t(triangles)).value();
}

size_t scene_triangles(const lc::Scene& scene) {
    size_t n = 0;
    for (const lc::Mesh& mesh : scene.meshes) n += mesh.indices.size() / 3;
    return n;
}

// Bytes the BVH holds per kept triangle beyond the mesh: its binary and
// 4-wide nodes, the shaders' triangles and the CPU's double vertices.
double bvh_bytes_per_triangle(const lc::ShadowBvh& bvh) {
    const double bytes = double(bvh.gpu_nodes().size() * sizeof(lc::GpuBvhNode)) +
                         double(bvh.gpu_wide_nodes().size() * sizeof(lc::GpuWideBvhNode)) +
                         double(bvh.gpu_triangles().size() * sizeof(lc::GpuShadowTriangle)) +
                         double(bvh.stats().triangles) * 3.0 * sizeof(glm::dvec3);
    return bytes / double(bvh.stats().triangles);
}

void BM_ShadowBvhBuild(benchmark::State& state) {
    const lc::Scene scene = scene_of(state.range(0));
    lc::ShadowBvh bvh;
    for (auto _ : state) {
        bvh = lc::ShadowBvh::build(scene);
        benchmark::DoNotOptimize(bvh.gpu_nodes().data());
    }
    state.counters["triangles"] = double(scene_triangles(scene));
    state.counters["nodes"] = double(bvh.stats().nodes);
    state.counters["depth"] = double(bvh.stats().depth);
    state.counters["bytes_per_triangle"] = bvh_bytes_per_triangle(bvh);
}

void BM_ShadowRay(benchmark::State& state) {
    const lc::Scene scene = scene_of(state.range(0));
    const lc::ShadowBvh bvh = lc::ShadowBvh::build(scene);
    const std::vector<Ray> rays = room_rays(4096);
    size_t occluded = 0, traced = 0;
    for (auto _ : state) {
        for (const Ray& r : rays) occluded += bvh.occluded(r.origin, r.direction, 1.0);
        traced += rays.size();
    }
    state.SetItemsProcessed(int64_t(traced));
    state.counters["triangles"] = double(scene_triangles(scene));
    state.counters["occluded_fraction"] = double(occluded) / double(std::max<size_t>(traced, 1));
    state.counters["seconds_per_ray"] =
        benchmark::Counter(double(traced), benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}

}  // namespace

// 0: the furnished room alone.
BENCHMARK(BM_ShadowBvhBuild)->Arg(0)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_ShadowRay)->Arg(0)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

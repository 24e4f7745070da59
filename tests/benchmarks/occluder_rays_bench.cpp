// Shadow rays per second on the CPU (ShadowBvh::occluded through
// light_visibility, as the CPU evaluator casts them): the furnished room with
// 16,384 random point lights (scripts/lib/furnished_bench.sh's scene) or the
// heavy room's sphere, rays from area-weighted random surface points to 16
// random lights each. One fixed seed: the same rays for every build, so
// scripts/bench/occluders.sh compares builds of this file before and after.
#include <benchmark/benchmark.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "editor_client/scene/heavy_mesh.h"
#include "editor_client/scene/scene_generator.h"
#include "lightcuts/occlusion/shadow_bvh.h"
#include "lightcuts/occlusion/shadow_ray.h"

namespace {

constexpr uint32_t kLights = 16384;
constexpr size_t kPoints = 4096;
constexpr size_t kLightsPerPoint = 16;

struct ShadingPoint {
    glm::dvec3 position;
    glm::dvec3 normal;
};

// [0, 1) from the top 53 bits: the same on every standard library.
double unit(std::mt19937_64& rng) { return double(rng() >> 11) * 0x1p-53; }

lc::Scene scene_of(int64_t triangles) {
    if (triangles == 0) return lc::client::make_furnished_room_scene();
    return lc::client::make_heavy_room_scene(uint32_t(triangles)).value();
}

// Area-weighted points on the scene's triangles with their geometric normals.
std::vector<ShadingPoint> surface_points(const lc::Scene& scene, size_t count, std::mt19937_64& rng) {
    std::vector<glm::dvec3> corners;
    std::vector<double> cumulative_area;
    double total = 0.0;
    for (const lc::Mesh& mesh : scene.meshes) {
        for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
            const glm::dvec3 a(mesh.positions[mesh.indices[t]]);
            const glm::dvec3 b(mesh.positions[mesh.indices[t + 1]]);
            const glm::dvec3 c(mesh.positions[mesh.indices[t + 2]]);
            const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
            if (!(area > 0.0)) continue;
            total += area;
            cumulative_area.push_back(total);
            corners.insert(corners.end(), {a, b, c});
        }
    }
    std::vector<ShadingPoint> points(count);
    for (ShadingPoint& p : points) {
        const size_t t = size_t(std::upper_bound(cumulative_area.begin(), cumulative_area.end(), unit(rng) * total) -
                                cumulative_area.begin());
        const size_t k = 3 * std::min(t, cumulative_area.size() - 1);
        double u = unit(rng), v = unit(rng);
        if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
        const glm::dvec3& a = corners[k];
        p.position = a + u * (corners[k + 1] - a) + v * (corners[k + 2] - a);
        p.normal = glm::normalize(glm::cross(corners[k + 1] - a, corners[k + 2] - a));
    }
    return points;
}

void BM_OccluderRays(benchmark::State& state) {
    const lc::Scene scene = scene_of(state.range(0));
    const lc::ShadowBvh bvh = lc::ShadowBvh::build(scene);
    const double bias = lc::shadow_ray_bias(scene);
    lc::client::LightLayoutOptions options;
    options.count = kLights;
    options.seed = 1;
    options.box_min = lc::client::kRoomLightBoxMin;
    options.box_max = lc::client::kRoomLightBoxMax;
    const std::vector<lc::SceneLight> lights = lc::client::generate_lights(options).value();
    std::mt19937_64 rng(20261207u);
    const std::vector<ShadingPoint> points = surface_points(scene, kPoints, rng);
    std::vector<uint32_t> picks(kPoints * kLightsPerPoint);
    for (uint32_t& pick : picks) pick = uint32_t(rng() % lights.size());
    size_t visible = 0, traced = 0;
    for (auto _ : state) {
        for (size_t i = 0; i < picks.size(); ++i) {
            const ShadingPoint& p = points[i / kLightsPerPoint];
            const lc::SceneLight& light = lights[picks[i]];
            visible += size_t(lc::light_visibility(bvh, bias, lc::LightType::kPoint, glm::dvec3(light.position),
                                                   glm::dvec3(0.0), p.position, p.normal));
        }
        traced += picks.size();
    }
    state.SetItemsProcessed(int64_t(traced));
    state.counters["rays_per_s"] = benchmark::Counter(double(traced), benchmark::Counter::kIsRate);
    state.counters["visible_fraction"] = double(visible) / double(std::max<size_t>(traced, 1));
    state.counters["triangles"] = double(bvh.stats().triangles);
}

}  // namespace

// 0: the furnished room alone; else the heavy room's sphere of that many triangles.
BENCHMARK(BM_OccluderRays)->Arg(0)->Arg(100000)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();

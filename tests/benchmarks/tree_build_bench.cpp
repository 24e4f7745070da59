// Light-tree build time and memory per builder and light count. Run one case
// per process (scripts/bench/build.sh does) so peak RSS belongs to that case.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <cmath>
#include <random>
#include <vector>

#include "lightmass_server/builders/tree_builder.h"

namespace {

using lc::LightType;
using lc::SceneLight;

// Uniform point lights at a fixed density (about 1 per 1000 cubic units), so
// neighbourhoods look alike at every size; ranges cover a few neighbours.
std::vector<SceneLight> uniform_point_lights(uint32_t count) {
    std::mt19937_64 rng(20240601u + count);
    const float extent = 10.0f * std::cbrt(float(count));
    std::uniform_real_distribution<float> coordinate(0.0f, extent);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<SceneLight> lights(count);
    for (uint32_t i = 0; i < count; ++i) {
        SceneLight& light = lights[i];
        light.guid = lc::Guid{0x42454E43u, 0x48000000u, 0u, i + 1};
        light.type = LightType::kPoint;
        light.position = glm::vec3(coordinate(rng), coordinate(rng), coordinate(rng));
        light.color = glm::vec3(0.5f + unit(rng), 0.5f + unit(rng), 0.5f + unit(rng));
        light.intensity = 1.0f + 9.0f * unit(rng);
        light.range = 30.0f;
    }
    return lights;
}

// The paper's cluster metric summed over the tree's clusters (point lights:
// I_C * alpha_C^2), from the exported tree: a quality figure across builders.
double total_cluster_metric(const lc::LightTree& tree) {
    double total = 0.0;
    for (const lc::LightTreeNode& node : tree.nodes) {
        if (node.is_leaf()) continue;
        const glm::dvec3 diagonal = glm::dvec3(node.bbox_max) - glm::dvec3(node.bbox_min);
        const double I_C = double(node.intensity.x) + node.intensity.y + node.intensity.z;
        total +=
            I_C * (diagonal.x * diagonal.x + diagonal.y * diagonal.y + diagonal.z * diagonal.z);
    }
    return total;
}

double peak_rss_mb() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return double(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

void run_build(benchmark::State& state, lc::BuilderKind builder, lc::PairingMode pairing) {
    const uint32_t count = uint32_t(state.range(0));
    const std::vector<SceneLight> lights = uniform_point_lights(count);
    lc::bake::BuildOptions options;
    options.builder = builder;
    options.pairing = pairing;
    options.seed = 1;
    lc::bake::BuildReport report;
    double metric = 0.0;
    for (auto _ : state) {
        lc::Result<lc::bake::BuildResult> built = lc::bake::build_light_tree(lights, options, {});
        if (!built) {
            state.SkipWithError(built.error().c_str());
            return;
        }
        report = built->report;
        state.PauseTiming();
        metric = total_cluster_metric(built->tree);
        state.ResumeTiming();
    }
    state.counters["lights"] = count;
    state.counters["build_ms"] = report.build_ms;
    state.counters["pairing_cost"] = report.pairing_cost;
    state.counters["lower_bound"] = report.pairing_lower_bound;
    state.counters["exact"] = report.exact ? 1 : 0;
    state.counters["depth"] = report.depth;
    state.counters["cluster_metric"] = metric;
    state.counters["peak_rss_mb"] = peak_rss_mb();
    for (const lc::bake::BuildPhase& phase : report.phases) state.counters["ms " + phase.name] = phase.ms;
}

void optimal_pair_exact(benchmark::State& state) {
    run_build(state, lc::BuilderKind::kOptimalPair, lc::PairingMode::kExact);
}
void optimal_pair_approximate(benchmark::State& state) {
    run_build(state, lc::BuilderKind::kOptimalPair, lc::PairingMode::kApproximate);
}
void agglomerative(benchmark::State& state) {
    run_build(state, lc::BuilderKind::kAgglomerative, lc::PairingMode::kAuto);
}
void lbvh(benchmark::State& state) {
    run_build(state, lc::BuilderKind::kLbvh, lc::PairingMode::kAuto);
}

BENCHMARK(optimal_pair_exact)
    ->RangeMultiplier(2)
    ->Range(256, 4096)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(optimal_pair_approximate)
    ->Arg(4096)
    ->Arg(16384)
    ->Arg(65536)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(agglomerative)
    ->RangeMultiplier(2)
    ->Range(1 << 10, 1 << 20)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(lbvh)
    ->RangeMultiplier(4)
    ->Range(1 << 10, 1 << 20)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

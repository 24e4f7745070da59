// Area lights: sampling emissive triangles into oriented lights, then the
// tree build over them, for 10^4, 10^5 and 10^6 samples (scripts/
// bench/area_lights.sh writes docs/bench/area_lights_build.csv).
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>

#include "lightmass_server/emitters/area_light_sampler.h"
#include "lightmass_server/builders/tree_builder.h"

namespace {

// A ceiling of 64 x 64 emissive quads (8,192 triangles) over 20 x 20 m, their
// radiance varying across it, facing down.
lc::SceneGeometry emissive_ceiling() {
    constexpr int kQuads = 64;
    constexpr float kCell = 20.0f / kQuads;
    lc::SceneGeometry g;
    for (int i = 0; i < kQuads; ++i) {
        for (int j = 0; j < kQuads; ++j) {
            lc::SurfaceMaterial m;
            m.emission = glm::vec3(1.0f + float((i * 7 + j * 3) % 11), 4.0f, 2.0f + float(j % 5));
            g.materials.push_back(m);
            const glm::vec3 c(float(i) * kCell - 10.0f, 3.0f, float(j) * kCell - 10.0f);
            const glm::vec3 corners[4] = {c, c + glm::vec3(kCell, 0, 0), c + glm::vec3(kCell, 0, kCell),
                                          c + glm::vec3(0, 0, kCell)};
            for (int k = 0; k < 2; ++k) {
                lc::SurfaceTriangle t;
                t.positions[0] = corners[0];
                t.positions[1] = corners[k == 0 ? 2 : 3];
                t.positions[2] = corners[k == 0 ? 1 : 2];
                t.normals[0] = t.normals[1] = t.normals[2] = glm::vec3(0, -1, 0);
                t.material = uint32_t(g.materials.size() - 1);
                g.triangles.push_back(t);
            }
        }
    }
    return g;
}

void run(benchmark::State& state, lc::BuilderKind builder) {
    const uint32_t samples = uint32_t(state.range(0));
    const lc::SceneGeometry geometry = emissive_ceiling();
    lc::bake::BuildOptions options;
    options.builder = builder;
    options.seed = 1;
    double sample_ms = 0.0, build_ms = 0.0;
    size_t lights = 0;
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        lc::Result<lc::bake::AreaLightSampling> sampled = lc::bake::sample_area_lights(geometry, samples, 1);
        sample_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (!sampled) {
            state.SkipWithError(sampled.error().c_str());
            return;
        }
        lc::Result<lc::bake::BuildResult> built = lc::bake::build_light_tree(sampled->lights, options, {});
        if (!built) {
            state.SkipWithError(built.error().c_str());
            return;
        }
        build_ms = built->report.build_ms;
        lights = sampled->lights.size();
    }
    state.counters["samples"] = double(lights);
    state.counters["triangles"] = double(geometry.triangles.size());
    state.counters["sample_ms"] = sample_ms;
    state.counters["build_ms"] = build_ms;
}

void agglomerative(benchmark::State& state) { run(state, lc::BuilderKind::kAgglomerative); }
void lbvh(benchmark::State& state) { run(state, lc::BuilderKind::kLbvh); }

BENCHMARK(agglomerative)->Arg(10000)->Arg(100000)->Arg(1000000)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(lbvh)->Arg(10000)->Arg(100000)->Arg(1000000)->Iterations(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();

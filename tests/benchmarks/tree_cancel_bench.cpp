// How long an optimal-pair tree build takes to return once its BakeStop is
// cancelled (issue 27: every stage within 100 ms). The build runs on its own
// thread; the main thread cancels it at delays spread over the build, whose
// levels all pair exactly at the default limit, and times cancel() to return.
//   tree_cancel_bench [LIGHTS=32768] [CANCELS=8] >> docs/bench/tree_cancel.csv
// Prints CSV: lights,cancel_after_ms,outcome,latency_ms,full_build_ms.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <thread>
#include <vector>

#include "lightmass_server/tree_builder.h"

namespace {

using Clock = std::chrono::steady_clock;
using lc::SceneLight;

// Uniform point lights (about one per 1000 cubic units), seed fixed per count.
std::vector<SceneLight> uniform_point_lights(uint32_t count) {
    std::mt19937_64 rng(20261127u + count);
    const float extent = 10.0f * std::cbrt(float(count));
    std::uniform_real_distribution<float> coordinate(0.0f, extent);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<SceneLight> lights(count);
    for (uint32_t i = 0; i < count; ++i) {
        SceneLight& light = lights[i];
        light.guid = lc::Guid{0x43414E43u, 0x454C0000u, 0u, i + 1};
        light.type = lc::LightType::kPoint;
        light.position = glm::vec3(coordinate(rng), coordinate(rng), coordinate(rng));
        light.color = glm::vec3(0.5f + unit(rng));
        light.intensity = 1.0f + 9.0f * unit(rng);
        light.range = 30.0f;
    }
    return lights;
}

double ms_between(Clock::time_point a, Clock::time_point b) {
    return std::chrono::duration<double, std::milli>(b - a).count();
}

struct CancelOutcome {
    bool cancelled = false;
    double latency_ms = 0.0;
};

CancelOutcome cancel_build_after(const std::vector<SceneLight>& lights, double delay_ms) {
    lc::bake::BakeStop stop;
    lc::bake::BuildOptions options;
    options.seed = 7;
    options.stop = &stop;
    bool cancelled = false;
    Clock::time_point returned;
    std::thread builder([&] {
        auto built = lc::bake::build_light_tree(lights, options, nullptr);
        returned = Clock::now();
        cancelled = !built && built.error_kind() == lc::ErrorKind::kCancelled;
    });
    std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(delay_ms));
    const Clock::time_point asked = Clock::now();
    stop.cancel();
    builder.join();
    return CancelOutcome{cancelled, ms_between(asked, returned)};
}

}  // namespace

int main(int argc, char** argv) {
    const uint32_t light_count = argc > 1 ? uint32_t(std::strtoul(argv[1], nullptr, 10)) : 32768u;
    const int cancels = argc > 2 ? std::atoi(argv[2]) : 8;
    const std::vector<SceneLight> lights = uniform_point_lights(light_count);

    const Clock::time_point start = Clock::now();
    auto full = lc::bake::build_light_tree(lights, lc::bake::BuildOptions{.seed = 7}, nullptr);
    const double full_ms = ms_between(start, Clock::now());
    if (!full) {
        std::fprintf(stderr, "the uncancelled build failed: %s\n", full.error().c_str());
        return 1;
    }
    // Cancel points spread evenly over the build, ending before its last 5 %.
    for (int i = 0; i < cancels; ++i) {
        const double delay_ms = full_ms * 0.95 * (i + 0.5) / cancels;
        const CancelOutcome outcome = cancel_build_after(lights, delay_ms);
        std::printf("%u,%.0f,%s,%.1f,%.0f\n", light_count, delay_ms,
                    outcome.cancelled ? "cancelled" : "finished", outcome.latency_ms, full_ms);
    }
    return 0;
}

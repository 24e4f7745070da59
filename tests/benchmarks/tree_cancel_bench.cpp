// How long an optimal-pair tree build takes to return once its BakeStop is
// cancelled (issue 27: every stage within 100 ms). The build runs on its own
// thread; the main thread cancels it at delays spread over the build and times
// cancel() to return. At 32,768 lights (the default limit) every level pairs
// exactly; above it the first levels pair approximately.
//   tree_cancel_bench [LIGHTS=32768, even] [CANCELS=8] [DELAYS_MS=a,b,...]
//   (scripts/fault_test.sh tree-cancel); with DELAYS_MS, cancelled at those
//   delays only, the full builds skipped (their column reads 0).
//   tree_cancel_bench LIGHTS hash: the built tree's bytes hashed (no cancel).
// Prints CSV: lights,cancel_after_ms,outcome,latency_ms,full_build_ms, the
// full build timed with a live, never-cancelled stop (what the server runs);
// a "finished" row's latency is negative: the build returned before the cancel.
// On stderr: the first level's LEMON run, its stop polls and the work between
// two polls, and the full build without a stop (the polls' cost).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string_view>
#include <thread>
#include <vector>

#include "lightmass_server/builders/approximate_pairing.h"
#include "lightmass_server/builders/min_weight_matching.h"
#include "lightmass_server/builders/point_kd_tree.h"
#include "lightmass_server/builders/sparse_exact_pairing.h"
#include "lightmass_server/builders/tree_builder.h"
#include "protocol/channel_records.h"

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

// One LEMON run over the first level's candidate graph (its k-NN and feasible
// pairs, as exact_pairing builds it), counting the stop polls it makes.
void report_poll_interval(const std::vector<SceneLight>& lights) {
    std::vector<glm::dvec3> points;
    for (const SceneLight& light : lights) points.emplace_back(light.position);
    const lc::bake::ExactPairingOptions options;
    const lc::bake::KnnResult knn = lc::bake::k_nearest_neighbors(points, options.candidate_neighbors);
    std::vector<std::pair<uint32_t, uint32_t>> keys;
    for (uint32_t u = 0; u < points.size(); ++u) {
        for (const auto& nb : knn.of(u)) keys.emplace_back(std::min(u, nb.index), std::max(u, nb.index));
    }
    for (const auto& pair : lc::bake::approximate_pairing(points).pairs) keys.push_back(pair);
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<lc::bake::MatchingEdge> edges;
    for (const auto& [u, v] : keys) edges.push_back({u, v, glm::distance(points[u], points[v])});
    uint64_t polls = 0;
    const Clock::time_point start = Clock::now();
    auto matched = lc::bake::min_weight_perfect_matching(uint32_t(points.size()), edges, [&] {
        ++polls;
        return false;
    });
    const double run_ms = ms_between(start, Clock::now());
    std::fprintf(stderr, "level of %zu nodes: LEMON %.0f ms, %llu stop polls, %.3f ms between polls%s\n",
                 points.size(), run_ms, (unsigned long long)polls,
                 run_ms / double(std::max<uint64_t>(polls, 1)), matched ? "" : " (failed)");
}

}  // namespace

// FNV-1a of the tree's result-channel bytes, built without a stop and with a
// live one: equal before and after a change to the builder means the same trees.
int print_tree_hashes(const std::vector<SceneLight>& lights) {
    lc::bake::BakeStop live;
    const lc::bake::BakeStop* const stops[] = {nullptr, &live};
    for (const lc::bake::BakeStop* stop : stops) {
        const Clock::time_point start = Clock::now();
        auto built = lc::bake::build_light_tree(lights, lc::bake::BuildOptions{.seed = 7, .stop = stop}, nullptr);
        if (!built) {
            std::fprintf(stderr, "build failed: %s\n", built.error().c_str());
            return 1;
        }
        const std::vector<uint8_t> bytes = lc::encode_result_channel(built->tree);
        uint64_t hash = 1469598103934665603ull;
        for (const uint8_t byte : bytes) hash = (hash ^ byte) * 1099511628211ull;
        std::printf("%zu lights, %s stop: %zu bytes, fnv1a %016llx, %.0f ms\n", lights.size(),
                    stop ? "a live" : "no", bytes.size(), (unsigned long long)hash, ms_between(start, Clock::now()));
    }
    return 0;
}

// "1500,4000,8000" -> {1500, 4000, 8000}.
std::vector<double> parse_delays(const char* text) {
    std::vector<double> delays;
    for (char* end = nullptr; *text; text = *end ? end + 1 : end) {
        delays.push_back(std::strtod(text, &end));
        if (end == text) break;
    }
    return delays;
}

int main(int argc, char** argv) {
    const uint32_t light_count = argc > 1 ? uint32_t(std::strtoul(argv[1], nullptr, 10)) : 32768u;
    const int cancels = argc > 2 ? std::atoi(argv[2]) : 8;
    const std::vector<SceneLight> lights = uniform_point_lights(light_count);
    if (argc > 2 && std::string_view(argv[2]) == "hash") return print_tree_hashes(lights);
    // Cancel delays given: the full builds (minutes at 4 M lights) are skipped
    // and the full_build_ms column reads 0.
    if (argc > 3) {
        for (const double delay_ms : parse_delays(argv[3])) {
            const CancelOutcome outcome = cancel_build_after(lights, delay_ms);
            std::printf("%u,%.0f,%s,%.1f,0\n", light_count, delay_ms,
                        outcome.cancelled ? "cancelled" : "finished", outcome.latency_ms);
            std::fflush(stdout);
        }
        return 0;
    }

    // One LEMON run over a level larger than the builder ever pairs exactly
    // would take minutes and gigabytes: measured up to the default limit only.
    if (light_count <= lc::bake::kDefaultExactPairingLimit) report_poll_interval(lights);
    Clock::time_point start = Clock::now();
    auto unstopped = lc::bake::build_light_tree(lights, lc::bake::BuildOptions{.seed = 7}, nullptr);
    std::fprintf(stderr, "full build without a stop: %.0f ms\n", ms_between(start, Clock::now()));
    lc::bake::BakeStop live;
    start = Clock::now();
    auto full = lc::bake::build_light_tree(lights, lc::bake::BuildOptions{.seed = 7, .stop = &live}, nullptr);
    const double full_ms = ms_between(start, Clock::now());
    if (!full || !unstopped) {
        std::fprintf(stderr, "an uncancelled build failed\n");
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

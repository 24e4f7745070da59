// Every heavy stage of a bake stops when its BakeStop asks (issue 27): the
// VPL tracer (and its cap on the lights it deposits), radiosity with point
// lights and patches shooting, area-light and environment sampling, and the
// whole pipeline. A cancel gives kCancelled; a deadline an error naming it.
// Stop latencies are measured by scripts/fault_test.sh hostile-bake, not here.
#include "lightmass_server/control/bake_stop.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <memory>

#include "indirect_scenes.h"
#include "lightmass_server/builders/approximate_pairing.h"
#include "lightmass_server/mpi/bake_dispatch.h"
#include "lightmass_server/emitters/area_light_sampler.h"
#include "lightmass_server/emitters/environment_sampler.h"
#include "lightmass_server/indirect/radiosity_solver.h"
#include "lightmass_server/indirect/vpl_tracer.h"
#include "protocol/channel_records.h"
#include "tree_invariants.h"

namespace lc::bake {
namespace {

// A closed white furnace: every path bounces until its bounce limit.
SceneGeometry white_furnace() {
    return test::closed_box({glm::vec3(1.0f), glm::vec3(1.0f)});
}

std::unique_ptr<BakeStop> cancelled_stop() {
    auto stop = std::make_unique<BakeStop>();
    stop->cancel();
    return stop;
}

std::unique_ptr<BakeStop> expired_stop() {
    return std::make_unique<BakeStop>(BakeStop::Clock::now(), "--max-bake-seconds 1");
}

SceneLight point_light_at(glm::vec3 position) {
    SceneLight light;
    light.type = LightType::kPoint;
    light.position = position;
    light.intensity = 1.0f;
    return light;
}

TEST(StopPoll, AsksTheClockOnlyEveryFewPollsAndLatches) {
    StopPoll never(nullptr);
    for (int i = 0; i < 1000; ++i) ASSERT_FALSE(never());
    auto stop = expired_stop();
    StopPoll poll(stop.get());
    int polls = 1;
    while (!poll()) ++polls;
    EXPECT_EQ(polls, int(StopPoll::kClockEvery));
    EXPECT_TRUE(poll());  // stays stopped
    auto cancelled = cancelled_stop();
    StopPoll at_once(cancelled.get());
    EXPECT_TRUE(at_once());  // a cancel needs no clock
}

TEST(BakeStop, ReasonSaysCancelledOrNamesTheDeadline) {
    EXPECT_EQ(cancelled_stop()->reason("radiosity").kind, ErrorKind::kCancelled);
    const Error late = expired_stop()->reason("radiosity");
    EXPECT_EQ(late.kind, ErrorKind::kFailed);
    EXPECT_NE(late.message.find("ran past --max-bake-seconds 1"), std::string::npos) << late.message;
}

TEST(VplTracerLimits, StopsAtItsLightCapInsteadOfGrowing) {
    // 1,000 paths in a white furnace run about 20 bounces each before Russian
    // roulette ends them (20,000 VPLs); a cap of 5,000 ends the trace with "too large".
    SceneGeometry g = white_furnace();
    auto caster = RayCaster::build(g, 1);
    ASSERT_TRUE(caster.ok());
    VplOptions options;
    options.particle_count = 1000;
    options.bounces = kMaxVplBounces;
    options.max_lights = 5000;
    auto traced = trace_vpls(g, *caster, {}, options, {});
    ASSERT_FALSE(traced.ok());
    EXPECT_EQ(traced.error_kind(), ErrorKind::kRefused);
    EXPECT_NE(traced.error().find("too large"), std::string::npos) << traced.error();
    EXPECT_NE(traced.error().find("5000 VPLs"), std::string::npos) << traced.error();
}

TEST(VplTracerLimits, CancelAndDeadlineStopTheTraceInsideABatch) {
    SceneGeometry g = white_furnace();
    auto caster = RayCaster::build(g, 1);
    ASSERT_TRUE(caster.ok());
    VplOptions options;
    options.particle_count = 1000;  // one batch, 65 million bounces
    options.bounces = kMaxVplBounces;
    options.max_lights = uint64_t{1} << 40;
    auto cancelled = cancelled_stop();
    options.stop = cancelled.get();
    auto traced = trace_vpls(g, *caster, {}, options, {});
    ASSERT_FALSE(traced.ok());
    EXPECT_EQ(traced.error_kind(), ErrorKind::kCancelled);
    auto late = expired_stop();
    options.stop = late.get();
    traced = trace_vpls(g, *caster, {}, options, {});
    ASSERT_FALSE(traced.ok());
    EXPECT_NE(traced.error().find("--max-bake-seconds"), std::string::npos) << traced.error();
}

TEST(RadiosityLimits, PointLightsAndShootingStopWhenAsked) {
    SceneGeometry g = test::closed_box({glm::vec3(0.5f), glm::vec3(0.0f)});
    auto caster = RayCaster::build(g, 1);
    ASSERT_TRUE(caster.ok());
    const std::vector<SceneLight> lights(50, point_light_at({0.5f, 0.5f, 0.5f}));
    RadiosityOptions options;
    options.patch_size = 0.25f;  // 432 patches: the unstopped solve converges in well under a second
    auto cancelled = cancelled_stop();
    options.stop = cancelled.get();
    auto solved = solve_radiosity(g, *caster, lights, options, {});
    ASSERT_FALSE(solved.ok());
    EXPECT_EQ(solved.error_kind(), ErrorKind::kCancelled);
    auto late = expired_stop();
    options.stop = late.get();
    solved = solve_radiosity(g, *caster, lights, options, {});
    ASSERT_FALSE(solved.ok());
    EXPECT_NE(solved.error().find("radiosity stopped"), std::string::npos) << solved.error();
    options.stop = nullptr;  // the same solve, unstopped, converges
    EXPECT_TRUE(solve_radiosity(g, *caster, lights, options, {}).ok());
}

TEST(EmitterSamplingLimits, AreaAndEnvironmentSamplingStopWhenAsked) {
    SceneGeometry g = test::closed_box({glm::vec3(0.5f), glm::vec3(1.0f)});
    auto cancelled = cancelled_stop();
    auto area = sample_area_lights(g, 100000, 1, IndexRange{}, cancelled.get());
    ASSERT_FALSE(area.ok());
    EXPECT_EQ(area.error_kind(), ErrorKind::kCancelled);
    EXPECT_TRUE(sample_area_lights(g, 1000, 1).ok());

    Environment environment;
    environment.map.width = 64;
    environment.map.height = 32;
    environment.map.texels.assign(64 * 32, glm::vec3(1.0f));
    auto late = expired_stop();
    auto sky = sample_environment(environment, 5000, 1, 0, 1, late.get());
    ASSERT_FALSE(sky.ok());
    EXPECT_NE(sky.error().find("environment sampling stopped"), std::string::npos) << sky.error();
    EXPECT_TRUE(sample_environment(environment, 5000, 1).ok());
}

TEST(TreeBuildLimits, ApproximatePairingStopsInsideALevel) {
    const std::vector<SceneLight> lights = test::random_lights(20000, 5, LightType::kPoint);
    std::vector<glm::dvec3> points;
    for (const SceneLight& light : lights) points.emplace_back(light.position);
    auto cancelled = cancelled_stop();
    EXPECT_TRUE(approximate_pairing(points, cancelled.get()).pairs.empty());
    EXPECT_EQ(approximate_pairing(points).pairs.size(), 10000u);
    BuildOptions options;
    options.pairing = PairingMode::kApproximate;
    options.stop = cancelled.get();
    auto built = build_light_tree(lights, options, nullptr);
    ASSERT_FALSE(built.ok());
    EXPECT_EQ(built.error_kind(), ErrorKind::kCancelled);
    EXPECT_NE(built.error().find("optimal-pair level 0"), std::string::npos) << built.error();
}

// The exact levels stop too (LEMON's run is polled from inside: the
// matching's own test counts its polls), and a stop that is never asked leaves
// the tree byte for byte what it is without one, at any thread count.
TEST(TreeBuildLimits, ExactPairingStopsInsideALevelAndALiveStopChangesNoTree) {
    const std::vector<SceneLight> lights = test::random_lights(3000, 6, LightType::kPoint);
    BuildOptions options;
    options.pairing = PairingMode::kExact;
    options.seed = 3;
    auto cancelled = cancelled_stop();
    options.stop = cancelled.get();
    auto stopped = build_light_tree(lights, options, nullptr);
    ASSERT_FALSE(stopped.ok());
    EXPECT_EQ(stopped.error_kind(), ErrorKind::kCancelled);
    EXPECT_NE(stopped.error().find("optimal-pair level 0 (exact pairing)"), std::string::npos)
        << stopped.error();

    options.stop = nullptr;
    auto unstopped = build_light_tree(lights, options, nullptr);
    ASSERT_TRUE(unstopped.ok()) << unstopped.error();
    EXPECT_TRUE(unstopped->report.exact);
    BakeStop live;
    options.stop = &live;
    for (const size_t threads : {1u, 2u, 4u}) {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        auto built = build_light_tree(lights, options, nullptr);
        ASSERT_TRUE(built.ok()) << built.error();
        EXPECT_EQ(encode_result_channel(built->tree), encode_result_channel(unstopped->tree))
            << threads << " threads";
    }
}

TEST(BakePipelineLimits, AStoppedBakeEndsWithTheStopsReason) {
    BakeInputs inputs;
    inputs.lights =
        std::make_shared<const std::vector<SceneLight>>(test::random_lights(2000, 3, LightType::kPoint));
    inputs.geometry = std::make_shared<const SceneGeometry>(white_furnace());
    inputs.indirect.method = IndirectMethod::kVpl;
    inputs.indirect.vpl.bounces = kMaxVplBounces;
    inputs.stop = std::make_shared<BakeStop>();
    inputs.stop->cancel();
    auto baked = run_bake(inputs, {});
    ASSERT_FALSE(baked.ok());
    EXPECT_EQ(baked.error_kind(), ErrorKind::kCancelled);
    inputs.stop = std::make_shared<BakeStop>(BakeStop::Clock::now(), "--max-bake-seconds 1");
    baked = run_bake(inputs, {});
    ASSERT_FALSE(baked.ok());
    EXPECT_NE(baked.error().find("ran past --max-bake-seconds 1"), std::string::npos) << baked.error();
}

}  // namespace
}  // namespace lc::bake

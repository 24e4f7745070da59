// End to end over loopback with a separately started lightmass_server: an
// environment map and a sun and sky baked into the tree as directional
// lights, byte-identical at --threads 1 and 2, and bad budgets or texels
// refused with the previous tree kept.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "editor_client/bake/bake_client.h"
#include "editor_client/bake/server_process.h"
#include "editor_client/bake/tree_store.h"
#include "lightcuts/seeded_mixer.h"
#include "test_paths.h"

namespace lc {
namespace {

using client::BakeClientOptions;
using client::ServerProcess;

const Guid kSceneGuid{5, 6, 7, 8};

std::unique_ptr<ServerProcess> start_server(unsigned threads) {
    auto server = ServerProcess::spawn_with((test::bin_dir() / "lightmass_server").string(),
                                            {"--quiet", "--listen", "127.0.0.1:0", "--threads", std::to_string(threads)});
    EXPECT_TRUE(server.ok()) << (server.ok() ? "" : server.error());
    return server.ok() ? std::move(server.value()) : nullptr;
}

std::vector<SceneLight> scene_lights() {
    std::vector<SceneLight> lights;
    for (uint32_t i = 0; i < 5; ++i) {
        SceneLight light;
        light.guid = Guid{0x2000u + i, 0, 0, i};
        light.position = {float(i), 2.0f, -float(i)};
        light.intensity = 10.0f + float(i);
        lights.push_back(light);
    }
    return lights;
}

std::shared_ptr<const Environment> random_map_environment() {
    auto environment = std::make_shared<Environment>();
    environment->map = EquirectMap{64, 32, {}};
    SplitMix64 random(17);
    for (int i = 0; i < 64 * 32; ++i)
        environment->map.texels.push_back(glm::vec3(float(random.uniform()), float(random.uniform()), 0.5f));
    environment->map.texels[300] = glm::vec3(200.0f);
    environment->rotation_deg = 25.0f;
    return environment;
}

BakeClientOptions options_for(const ServerProcess& server, std::shared_ptr<const Environment> environment,
                              uint32_t environment_lights) {
    BakeClientOptions options;
    options.server = server.address();
    options.timeout_seconds = 120.0;
    options.seed = 3;
    options.environment = std::move(environment);
    options.environment_lights = environment_lights;
    return options;
}

size_t directional_leaves(const LightTree& tree) {
    size_t count = 0;
    for (const LightTreeNode& node : tree.nodes)
        count += node.left < 0 && node.right < 0 && node.type == LightType::kDirectional;
    return count;
}

TEST(EnvironmentBake, MapBakesByteIdenticallyAtOneAndTwoThreads) {
    auto one = start_server(1);
    auto two = start_server(2);
    ASSERT_TRUE(one && two);
    const auto environment = random_map_environment();
    auto a = client::bake_lights(scene_lights(), kSceneGuid, options_for(*one, environment, 1500));
    auto b = client::bake_lights(scene_lights(), kSceneGuid, options_for(*two, environment, 1500));
    auto again = client::bake_lights(scene_lights(), kSceneGuid, options_for(*two, environment, 1500));
    ASSERT_TRUE(a) << a.error();
    ASSERT_TRUE(b) << b.error();
    ASSERT_TRUE(again) << again.error();
    EXPECT_EQ(a->tree.leaf_count, 5u + 1500u);
    EXPECT_EQ(directional_leaves(a->tree), 1500u);
    EXPECT_EQ(a->result_channel, b->result_channel);
    EXPECT_EQ(b->result_channel, again->result_channel);
}

TEST(EnvironmentBake, SunAndSkyBecomeTheDefaultBudgetAndTheCensusIsAStage) {
    auto server = start_server(2);
    ASSERT_TRUE(server);
    auto environment = std::make_shared<Environment>();
    environment->sky = SkyParameters{35.0f, 60.0f, 3.0f};
    BakeClientOptions options = options_for(*server, environment, 0);
    std::vector<std::string> stages;
    options.on_progress = [&](const ProgressMsg& p) { stages.push_back(p.stage); };
    auto outcome = client::bake_lights(scene_lights(), kSceneGuid, options);
    ASSERT_TRUE(outcome) << outcome.error();
    EXPECT_EQ(directional_leaves(outcome->tree), kDefaultEnvironmentLights);
    bool census = false;
    for (const std::string& stage : stages) census = census || stage.starts_with("sun and sky: simulated (38 sun");
    EXPECT_TRUE(census);
}

TEST(EnvironmentBake, WithoutAnEnvironmentTheTreeIsTheScenesAlone) {
    auto server = start_server(1);
    ASSERT_TRUE(server);
    auto plain = client::bake_lights(scene_lights(), kSceneGuid, options_for(*server, nullptr, 0));
    ASSERT_TRUE(plain) << plain.error();
    EXPECT_EQ(plain->tree.leaf_count, 5u);
    EXPECT_EQ(directional_leaves(plain->tree), 0u);
}

TEST(EnvironmentBake, AbsurdBudgetOrBadTexelFailsAndKeepsThePreviousTree) {
    auto server = start_server(1);
    ASSERT_TRUE(server);
    client::TreeStore store;
    ASSERT_TRUE(store.import(client::bake_lights(scene_lights(), kSceneGuid, options_for(*server, nullptr, 0))));
    const auto previous = store.current();

    Status absurd = store.import(client::bake_lights(
        scene_lights(), kSceneGuid, options_for(*server, random_map_environment(), kMaxEnvironmentLights + 1)));
    ASSERT_FALSE(absurd);
    EXPECT_NE(absurd.error().find(std::to_string(kMaxEnvironmentLights)), std::string::npos) << absurd.error();

    auto bad = std::make_shared<Environment>(*random_map_environment());
    bad->map.texels[77] = glm::vec3(std::numeric_limits<float>::quiet_NaN());
    Status refused = store.import(client::bake_lights(scene_lights(), kSceneGuid, options_for(*server, bad, 100)));
    ASSERT_FALSE(refused);
    EXPECT_NE(refused.error().find("texel (13, 1)"), std::string::npos) << refused.error();
    EXPECT_EQ(store.current(), previous);
}

}  // namespace
}  // namespace lc

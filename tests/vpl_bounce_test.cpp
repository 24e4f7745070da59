// The bounce each VPL carries from the tracer to the client
// (FLightData.light_source_length, docs/PROTOCOL.md): recorded by the tracer,
// kept by the builder and the wire, refused where it means nothing, and read
// by the render's census of a tree from a dump.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <vector>

#include "editor_client/render/analysis/indirect_census.h"
#include "indirect_scenes.h"
#include "lightmass_server/indirect/indirect_stage.h"
#include "lightmass_server/indirect/vpl_tracer.h"
#include "lightmass_server/builders/tree_builder.h"
#include "protocol/channel_records.h"

namespace lc {
namespace {

constexpr uint32_t kBounces = 4;

std::vector<bake::IndirectLight> traced_vpls(uint32_t bounces) {
    // A white-ish furnace: most paths survive several bounces.
    SceneGeometry g = test::closed_box({glm::vec3(0.8f), glm::vec3(1.0f)});
    auto caster = RayCaster::build(g, 1);
    EXPECT_TRUE(caster.ok());
    bake::VplOptions options;
    options.particle_count = 500;
    options.bounces = bounces;
    options.seed = 3;
    auto traced = bake::trace_vpls(g, *caster, {}, options, {});
    EXPECT_TRUE(traced.ok()) << traced.error();
    return traced.ok() ? traced->lights : std::vector<bake::IndirectLight>{};
}

// The VPLs as the bake adds them, beside two direct lights.
LightTree vpl_tree() {
    std::vector<SceneLight> lights = bake::as_tree_lights(traced_vpls(kBounces));
    for (float x : {0.2f, 0.8f}) {
        SceneLight direct;
        direct.position = {x, 0.5f, 0.5f};
        lights.push_back(direct);
    }
    auto built = bake::build_light_tree(lights, bake::BuildOptions{}, nullptr);
    EXPECT_TRUE(built.ok()) << built.error();
    return built.ok() ? built->tree : LightTree{};
}

TEST(VplBounce, TheTracerRecordsEachLightsBounceWithinTheRequest) {
    const std::vector<bake::IndirectLight> vpls = traced_vpls(kBounces);
    ASSERT_FALSE(vpls.empty());
    std::vector<size_t> per_bounce(kBounces + 1, 0);
    for (const bake::IndirectLight& l : vpls) {
        ASSERT_GE(l.bounce, 1u);
        ASSERT_LE(l.bounce, kBounces);
        ++per_bounce[l.bounce];
    }
    // Every particle deposits at its first hit in a closed box; fewer go on.
    EXPECT_EQ(per_bounce[1], 500u);
    for (uint32_t b = 2; b <= kBounces; ++b) {
        EXPECT_GT(per_bounce[b], 0u) << "bounce " << b;
        EXPECT_LE(per_bounce[b], per_bounce[b - 1]) << "bounce " << b;
    }
}

TEST(VplBounce, ARequestDeeperThanTheFieldIsRefusedNotTruncated) {
    SceneGeometry g = test::closed_box({glm::vec3(0.5f), glm::vec3(1.0f)});
    auto caster = RayCaster::build(g, 1);
    ASSERT_TRUE(caster.ok());
    bake::VplOptions options;
    options.particle_count = 10;
    options.bounces = bake::kMaxVplBounces + 1;
    auto traced = bake::trace_vpls(g, *caster, {}, options, {});
    ASSERT_FALSE(traced.ok());
    EXPECT_NE(traced.error().find("65536"), std::string::npos) << traced.error();
}

TEST(VplBounce, VplLeavesKeepTheirBounceOnTheWireAndNothingElseHasOne) {
    const LightTree tree = vpl_tree();
    ASSERT_FALSE(tree.empty());
    Result<LightTree> decoded = decode_result_channel(encode_result_channel(tree));
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    uint32_t vpl_leaves = 0;
    for (size_t i = 0; i < tree.nodes.size(); ++i) {
        const LightTreeNode& n = decoded->nodes[i];
        EXPECT_EQ(n.bounce, tree.nodes[i].bounce) << "node " << i;
        const bool vpl_leaf = n.is_leaf() && n.flags.indirect() && !n.flags.patch();
        vpl_leaves += vpl_leaf;
        if (vpl_leaf) {
            EXPECT_GE(n.bounce, 1u);
            EXPECT_LE(n.bounce, kBounces);
        } else {
            EXPECT_EQ(n.bounce, 0u) << "node " << i;
        }
    }
    EXPECT_GT(vpl_leaves, 500u);
    EXPECT_EQ(client::deepest_vpl_bounce(*decoded), kBounces);
}

TEST(VplBounce, ABounceWhereItMeansNothingIsRefused) {
    const LightTree tree = vpl_tree();
    ASSERT_FALSE(tree.empty());
    const auto refused_with = [&](const std::function<bool(const LightTreeNode&)>& which, const char* why) {
        LightTree bad = tree;
        std::find_if(bad.nodes.begin(), bad.nodes.end(), which)->bounce = 2;
        Result<LightTree> decoded = decode_result_channel(encode_result_channel(bad));
        ASSERT_FALSE(decoded.ok()) << why;
        EXPECT_NE(decoded.error().find("not a VPL leaf"), std::string::npos) << decoded.error();
    };
    refused_with([](const LightTreeNode& n) { return !n.is_leaf() && n.flags.indirect(); }, "a VPL cluster");
    refused_with([](const LightTreeNode& n) { return n.is_leaf() && !n.flags.indirect(); }, "a direct light");

    // On the wire the field is a float: a fraction or a negative is no bounce.
    std::vector<uint8_t> bytes = encode_result_channel(tree);
    const size_t vpl = size_t(std::find_if(tree.nodes.begin(), tree.nodes.end(), [](const LightTreeNode& n) {
                                  return n.is_leaf() && n.flags.indirect();
                              }) - tree.nodes.begin());
    // light_source_length: the count prefix, then FLightData's guid, flags,
    // three Vec4s, brightness and light_source_radius before it.
    const size_t at = 4 + vpl * result_record_bytes() + 16 + 4 + 48 + 4 + 4;
    for (float spoiled : {1.5f, -1.0f, 70000.0f}) {
        std::vector<uint8_t> bad = bytes;
        std::memcpy(bad.data() + at, &spoiled, sizeof spoiled);
        Result<LightTree> decoded = decode_result_channel(bad);
        ASSERT_FALSE(decoded.ok()) << spoiled;
        EXPECT_NE(decoded.error().find("light_source_length"), std::string::npos) << decoded.error();
    }

    // The builder refuses a bounce on a light that is no VPL.
    std::vector<SceneLight> lights(2);
    lights[1].position = {1.0f, 0.0f, 0.0f};
    lights[1].bounce = 1;
    EXPECT_FALSE(bake::build_light_tree(lights, bake::BuildOptions{}, nullptr).ok());
}

TEST(VplBounce, TheCensusOfATreeFromADumpSaysItsDeepestBounce) {
    client::IndirectCensusFacts f;
    f.has_tree = true;
    f.vpls = 2048;
    f.deepest_vpl_bounce = vpl_tree().nodes.empty() ? 0 : client::deepest_vpl_bounce(vpl_tree());
    EXPECT_EQ(client::indirect_census(f), "simulated (2048 VPLs, up to 4 bounces, clamped energy 0%)");
}

}  // namespace
}  // namespace lc

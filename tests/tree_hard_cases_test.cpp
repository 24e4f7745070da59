// SPEC §7's hard cases for every builder: empty and tiny scenes, odd counts,
// coincident lights, far-away lights, huge intensity ratios, dark lights,
// directional-only scenes, deep chains, and invalid input.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "lightmass_server/builders/agglomerative_builder.h"
#include "lightmass_server/builders/cluster_attributes.h"
#include "lightmass_server/builders/lbvh_builder.h"
#include "lightmass_server/builders/optimal_pair_builder.h"
#include "lightmass_server/builders/tree_builder.h"
#include "lightcuts/tree/tree_export.h"
#include "protocol/channel_records.h"
#include "tree_invariants.h"

namespace lc::bake {
namespace {

using test::expect_build_invariants;
using test::expect_tree_invariants;
using test::random_lights;

struct BuilderCase {
    const char* name;
    BuilderKind builder;
    PairingMode pairing;
};

const BuilderCase kBuilders[] = {
    {"optimal-pair exact", BuilderKind::kOptimalPair, PairingMode::kExact},
    {"optimal-pair approximate", BuilderKind::kOptimalPair, PairingMode::kApproximate},
    {"agglomerative", BuilderKind::kAgglomerative, PairingMode::kAuto},
    {"lbvh", BuilderKind::kLbvh, PairingMode::kAuto},
};

BuildOptions options_for(const BuilderCase& c, uint64_t seed = 11) {
    BuildOptions options;
    options.builder = c.builder;
    options.pairing = c.pairing;
    options.seed = seed;
    return options;
}

// Builds with every builder, twice: valid, finite, and byte-identical.
std::vector<BuildResult> build_everywhere(const std::vector<SceneLight>& lights) {
    std::vector<BuildResult> results;
    for (const BuilderCase& c : kBuilders) {
        SCOPED_TRACE(c.name);
        Result<BuildResult> first = build_light_tree(lights, options_for(c), {});
        Result<BuildResult> second = build_light_tree(lights, options_for(c), {});
        EXPECT_TRUE(first) << (first ? "" : first.error());
        EXPECT_TRUE(second);
        if (!first || !second) continue;
        expect_tree_invariants(first->tree, lights);
        const auto& a = first->tree.nodes;
        const auto& b = second->tree.nodes;
        EXPECT_EQ(a.size(), b.size());
        for (size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
            EXPECT_EQ(a[i].guid, b[i].guid) << i;
            EXPECT_EQ(a[i].left, b[i].left) << i;
            EXPECT_EQ(a[i].representative, b[i].representative) << i;
            EXPECT_EQ(std::memcmp(&a[i].bbox_min, &b[i].bbox_min, sizeof a[i].bbox_min), 0) << i;
            EXPECT_EQ(std::memcmp(&a[i].radius, &b[i].radius, sizeof a[i].radius), 0) << i;
        }
        EXPECT_TRUE(std::isfinite(first->report.pairing_cost));
        EXPECT_TRUE(std::isfinite(first->report.pairing_lower_bound));
        results.push_back(std::move(*first));
    }
    return results;
}

// The double-precision invariants for every builder.
void expect_build_invariants_everywhere(const std::vector<SceneLight>& lights) {
    const std::vector<uint32_t> leaves = test::all_indices(lights.size());
    for (const BuilderCase& c : kBuilders) {
        SCOPED_TRACE(c.name);
        BuildArena arena = test::leaf_arena(lights);
        BuildReport report;
        Result<int32_t> root = make_error("no builder");
        switch (c.builder) {
            case BuilderKind::kOptimalPair:
                root = build_optimal_pair_tree(arena, leaves, options_for(c), {}, report);
                break;
            case BuilderKind::kAgglomerative:
                root = build_agglomerative_tree(arena, leaves, options_for(c), {}, report);
                break;
            case BuilderKind::kLbvh:
                root = build_lbvh_tree(arena, leaves, options_for(c), {}, report);
                break;
        }
        ASSERT_TRUE(root) << root.error();
        expect_build_invariants(arena, *root, leaves);
    }
}

TEST(TreeHardCases, ZeroLightsGiveAnEmptyTree) {
    for (const BuildResult& r : build_everywhere({})) {
        EXPECT_TRUE(r.tree.empty());
        EXPECT_EQ(r.tree.leaf_count, 0u);
        EXPECT_EQ(r.report.depth, 0u);
    }
}

TEST(TreeHardCases, OneLightIsASingleLeafRoot) {
    const std::vector<SceneLight> lights = random_lights(1, 3, LightType::kSpot);
    for (const BuildResult& r : build_everywhere(lights)) {
        ASSERT_EQ(r.tree.nodes.size(), 1u);
        const LightTreeNode& root = r.tree.nodes[0];
        EXPECT_TRUE(root.is_leaf());
        EXPECT_EQ(root.representative, 0);
        EXPECT_EQ(root.guid, lights[0].guid);
        EXPECT_GE(root.radius, lights[0].range);
        EXPECT_LE(root.radius, std::nextafter(lights[0].range, INFINITY));
        EXPECT_EQ(r.report.levels, 0u);
    }
}

TEST(TreeHardCases, SmallOddAndPowerOfTwoPlusOneCounts) {
    for (uint32_t n : {2u, 3u, 5u, 7u, 9u, 17u, 33u, 65u, 129u, 257u}) {
        SCOPED_TRACE(n);
        const std::vector<SceneLight> lights = random_lights(n, n, LightType::kPoint);
        build_everywhere(lights);
        expect_build_invariants_everywhere(lights);
    }
}

TEST(TreeHardCases, CoincidentLightsTieDeterministically) {
    for (uint32_t n : {2u, 64u, 129u}) {
        std::vector<SceneLight> lights = random_lights(n, 5, LightType::kSpot);
        for (SceneLight& light : lights) {
            light.position = glm::vec3(3.0f, -7.0f, 2.5f);
            light.direction = glm::vec3(0.0f, 0.0f, -1.0f);
        }
        for (const BuildResult& r : build_everywhere(lights)) {
            const LightTreeNode& root = r.tree.nodes[0];
            EXPECT_EQ(root.bbox_min, glm::vec3(3.0f, -7.0f, 2.5f));
            EXPECT_EQ(root.bbox_max, glm::vec3(3.0f, -7.0f, 2.5f));
            EXPECT_LT(root.cone_cos, 1.0f);  // widened by the export margin only
            EXPECT_GT(root.cone_cos, 0.9999f);
        }
        expect_build_invariants_everywhere(lights);
    }
}

TEST(TreeHardCases, ManyCoincidentLightsStayFast) {
    // All-equal metrics must not make the searches quadratic.
    std::vector<SceneLight> lights = random_lights(20000, 8, LightType::kPoint);
    for (SceneLight& light : lights) light.position = glm::vec3(1.0f);
    BuildOptions options;
    options.builder = BuilderKind::kAgglomerative;
    Result<BuildResult> built = build_light_tree(lights, options, {});
    ASSERT_TRUE(built) << built.error();
    expect_tree_invariants(built->tree, lights);
    EXPECT_LT(built->report.depth, 64u);
}

TEST(TreeHardCases, FarFromTheOriginWithTinySeparations) {
    // 1e6 from the origin, 1e-3 apart: float positions round to a 0.0625 grid,
    // so many become coincident; nothing may overflow or lose a leaf.
    std::vector<SceneLight> lights = random_lights(101, 6, LightType::kPoint);
    for (uint32_t i = 0; i < lights.size(); ++i) {
        lights[i].position = glm::vec3(1e6f + 1e-3f * float(i), -1e6f, 1e6f - 1e-3f * float(i % 7));
        lights[i].range = 1e-3f;
    }
    for (const BuildResult& r : build_everywhere(lights)) {
        const LightTreeNode& root = r.tree.nodes[0];
        EXPECT_LE(root.bbox_min.x, 1e6f);
        EXPECT_GE(root.bbox_max.x, lights.back().position.x);
        EXPECT_GT(root.radius, 0.0f);
    }
    expect_build_invariants_everywhere(lights);
}

TEST(TreeHardCases, IntensityRatiosOfOneTrillion) {
    std::vector<SceneLight> lights = random_lights(200, 7, LightType::kPoint);
    for (uint32_t i = 0; i < lights.size(); ++i) {
        lights[i].intensity = i % 2 == 0 ? 1e6f : 1e-6f;
    }
    build_everywhere(lights);
    expect_build_invariants_everywhere(lights);
}

TEST(TreeHardCases, DarkLightsNeverRepresentLitClusters) {
    // I_A = 0 gives probability 0; all-dark clusters fall back to the first child.
    std::vector<SceneLight> lights = random_lights(150, 9, LightType::kPoint);
    for (uint32_t i = 0; i < lights.size(); ++i) {
        if (i % 3 != 0) lights[i].intensity = 0.0f;
    }
    for (const BuildResult& r : build_everywhere(lights)) {
        const LightTree& tree = r.tree;
        // Lit leaves below each node, bottom-up (children have larger indices).
        std::vector<int> lit(tree.nodes.size(), 0);
        for (size_t i = tree.nodes.size(); i-- > 0;) {
            const LightTreeNode& node = tree.nodes[i];
            lit[i] = node.is_leaf() ? (node.brightness > 0.0f ? 1 : 0)
                                    : lit[size_t(node.left)] + lit[size_t(node.right)];
            if (lit[i] > 0) {
                EXPECT_GT(tree.nodes[size_t(node.representative)].brightness, 0.0f) << i;
            }
        }
    }
    std::vector<SceneLight> dark = random_lights(40, 2, LightType::kPoint);
    for (SceneLight& light : dark) light.intensity = 0.0f;
    for (const BuildResult& r : build_everywhere(dark)) {
        EXPECT_EQ(r.tree.nodes[0].brightness, 0.0f);
        EXPECT_EQ(r.tree.nodes[0].intensity, glm::vec3(0.0f));
    }
    expect_build_invariants_everywhere(dark);
}

TEST(TreeHardCases, DirectionalLightsOnly) {
    const std::vector<SceneLight> lights = random_lights(77, 10, LightType::kDirectional);
    for (const BuildResult& r : build_everywhere(lights)) {
        for (const LightTreeNode& node : r.tree.nodes) {
            EXPECT_EQ(node.radius, kUnboundedRadius);
            EXPECT_EQ(node.type, LightType::kDirectional);
            EXPECT_FALSE(node.flags.mixed_types());
            for (int c = 0; c < 3; ++c) {
                EXPECT_GE(node.bbox_min[c], -1.0001f);
                EXPECT_LE(node.bbox_max[c], 1.0001f);
            }
        }
    }
    expect_build_invariants_everywhere(lights);
}

TEST(TreeHardCases, ExportedConesHoldEveryLeafDirection) {
    const std::vector<SceneLight> lights = random_lights(300, 12, LightType::kSpot);
    for (const BuildResult& r : build_everywhere(lights)) {
        const LightTree& tree = r.tree;
        std::vector<int32_t> parent(tree.nodes.size(), -1);
        for (size_t i = 0; i < tree.nodes.size(); ++i) {
            if (tree.nodes[i].is_leaf()) continue;
            parent[size_t(tree.nodes[i].left)] = int32_t(i);
            parent[size_t(tree.nodes[i].right)] = int32_t(i);
        }
        for (size_t i = 0; i < tree.nodes.size(); ++i) {
            if (!tree.nodes[i].is_leaf()) continue;
            // Float math on float data: the exported cone must still hold it.
            const glm::vec3 d = glm::normalize(tree.nodes[i].direction);
            for (int32_t a = parent[i]; a >= 0; a = parent[size_t(a)]) {
                const LightTreeNode& node = tree.nodes[size_t(a)];
                EXPECT_GE(glm::dot(node.cone_axis, d), node.cone_cos) << "node " << a;
            }
        }
    }
}

TEST(TreeHardCases, DeepChainsExportWithoutRecursion) {
    // A chain of depth 100000 (what a degenerate clustering could produce):
    // export, validation and invariants must all be iterative.
    const uint32_t n = 100000;
    std::vector<SceneLight> lights = random_lights(n, 13, LightType::kPoint);
    BuildArena arena = test::leaf_arena(lights);
    uint32_t chain = 0;
    for (uint32_t i = 1; i < n; ++i) {
        const BuildNode node = merge_clusters(arena, chain, i, RepresentativeRule::kIntensity, 1);
        chain = uint32_t(arena.nodes.size());
        arena.nodes.push_back(node);
    }
    const std::vector<uint32_t> leaves = test::all_indices(n);
    expect_build_invariants(arena, int32_t(chain), leaves);
    const ExportedTree exported = export_light_tree(arena, int32_t(chain));
    EXPECT_EQ(exported.depth, n - 1);
    EXPECT_EQ(exported.tree.leaf_count, n);
    const Status valid = validate_tree(exported.tree);
    EXPECT_TRUE(valid) << (valid ? "" : valid.error());
}

TEST(TreeHardCases, InvalidInputIsRejectedWithAMessage) {
    std::vector<SceneLight> lights = random_lights(5, 14, LightType::kPoint);
    const auto expect_rejected = [&](const std::vector<SceneLight>& bad, const std::string& word) {
        for (const BuilderCase& c : kBuilders) {
            Result<BuildResult> r = build_light_tree(bad, options_for(c), {});
            ASSERT_FALSE(r) << c.name;
            EXPECT_NE(r.error().find("light 2"), std::string::npos) << r.error();
            EXPECT_NE(r.error().find(word), std::string::npos) << r.error();
        }
    };
    std::vector<SceneLight> bad = lights;
    bad[2].position.x = std::numeric_limits<float>::quiet_NaN();
    expect_rejected(bad, "position");
    bad = lights;
    bad[2].intensity = std::numeric_limits<float>::infinity();
    expect_rejected(bad, "intensity");
    bad = lights;
    bad[2].intensity = -1.0f;
    expect_rejected(bad, "intensity");
    bad = lights;
    bad[2].color.y = -0.5f;
    expect_rejected(bad, "color");
    bad = lights;
    bad[2].range = -3.0f;
    expect_rejected(bad, "range");

    BuildOptions options;
    options.builder = BuilderKind(9);
    Result<BuildResult> unknown = build_light_tree(lights, options, {});
    ASSERT_FALSE(unknown);
    EXPECT_NE(unknown.error().find("builder"), std::string::npos) << unknown.error();
}

TEST(TreeHardCases, TheFirstBadLightIsNamedWhicheverThreadFindsIt) {
    // Validation runs in parallel chunks of 16,384 lights: with three bad
    // lights in different chunks, the error names the first in input order,
    // as the serial check did.
    std::vector<SceneLight> lights = random_lights(100000, 15, LightType::kPoint);
    lights[90001].range = -1.0f;
    lights[40001].intensity = -1.0f;
    lights[70001].color.x = -1.0f;
    Result<BuildResult> r = build_light_tree(lights, options_for(kBuilders[0]), {});
    ASSERT_FALSE(r);
    EXPECT_NE(r.error().find("light 40001 "), std::string::npos) << r.error();
    EXPECT_NE(r.error().find("intensity"), std::string::npos) << r.error();
}

}  // namespace
}  // namespace lc::bake

// A tree node shaded as a cluster: its representative's geometry with the
// cluster's summed intensity; a leaf is its own light.
#include <gtest/gtest.h>

#include <vector>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "tree_fixtures.h"

namespace lc::test {
namespace {

TEST(ShadeNode, LeafEqualsItsLightAndClusterUsesRepresentative) {
    std::vector<SceneLight> lights{make_light(LightType::kPoint, {0, 0, 2}, 2.0f, {1, 0, 0}),
                                   make_light(LightType::kPoint, {1, 0, 2}, 6.0f, {0, 0, 1})};
    const LightTree tree = morton_pairing_tree(lights, 1);
    ASSERT_EQ(tree.nodes.size(), 3u);
    const SurfacePoint p = surface({0.25, 0.5, 0});
    const WalkTree walk = walk_tree(tree);
    const LightTreeNode& root = tree.nodes[0];
    // The cluster: the representative's geometry with the summed RGB intensity.
    SceneLight as_cluster = make_light(LightType::kPoint, root.position, 1.0f, root.intensity);
    expect_near_rel(shade_node(walk, 0, p), shade_light(as_cluster, p), 1e-12);
    EXPECT_EQ(root.intensity, glm::vec3(2.0f, 0.0f, 6.0f));
    for (int c : {root.left, root.right}) {
        const LightTreeNode& leaf = tree.nodes[size_t(c)];
        const SceneLight& light = leaf.position == lights[0].position ? lights[0] : lights[1];
        expect_near_rel(shade_node(walk, c, p), shade_light(light, p), 1e-12);
    }
}

}  // namespace
}  // namespace lc::test

// The sum over a tree's leaves equals the reference over its lights, up to
// the float rounding of the stored nodes.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "tree_fixtures.h"

namespace lc::test {
namespace {

TEST(ShadeTreeLeaves, EqualsReferenceOnTheTreesLights) {
    std::mt19937_64 rng(11);
    std::vector<SceneLight> lights =
        random_lights_in_box(rng, 33, LightType::kSpot, {-4, -4, 1}, {4, 4, 3}, true);
    const LightTree tree = morton_pairing_tree(lights, 5);
    ASSERT_EQ(tree.leaf_count, 33u);
    const WalkTree walk = walk_tree(tree);
    for (int k = 0; k < 50; ++k) {
        std::uniform_real_distribution<double> u(-4, 4);
        const SurfacePoint p = surface({u(rng), u(rng), 0}, {u(rng) * 0.1, u(rng) * 0.1, 1});
        // The node stores its RGB intensity and spot cosines as floats; the spot
        // ramp divides by cos_inner - cos_outer (~0.01), so float rounding
        // reaches a few 1e-6 relative.
        expect_near_rel(shade_tree_leaves(walk, p), shade_reference(lights, p), 2e-5, 1e-12);
    }
}

}  // namespace
}  // namespace lc::test

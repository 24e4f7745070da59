#pragma once
// Shared by the evaluator's and the renderer's tests: lights and surface
// points built in code, the hand-made light trees (the thesis's Figure 9.1,
// a Morton-order pairing with SPEC §4's attributes, an index-order pairing),
// and the expectations that compare radiance.
#include <cstdint>
#include <numbers>
#include <random>
#include <vector>

#include <glm/vec3.hpp>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/tree/light_tree.h"
#include "lightcuts/scene_light.h"
#include "lightcuts/tree/walk_tree.h"

namespace lc::test {

inline constexpr double kPi = std::numbers::pi;

SceneLight make_light(LightType type, glm::vec3 position, float intensity, glm::vec3 color = glm::vec3(1.0f),
                      float range = 0.0f);

SurfacePoint surface(glm::dvec3 position, glm::dvec3 normal = {0, 0, 1}, glm::dvec3 albedo = {1, 1, 1});

// `count` lights of one type uniformly in the box [lo, hi], with random
// directions (pointing down), colours, intensities, ranges (when `ranged`)
// and cones; GUIDs {1, 2, 3, i + 1}.
std::vector<SceneLight> random_lights_in_box(std::mt19937_64& rng, int count, LightType type, glm::vec3 lo,
                                             glm::vec3 hi, bool ranged);

// 60 ranged points, 30 spots, 7 directional lights and 10 unbounded points in a 12 x 12 x 3.5 box.
std::vector<SceneLight> mixed_scene(std::mt19937_64& rng);

// The thesis's Figure 9.1 tree in its own coordinates (+Z up), breadth-first:
// 0 root (rep A, r 700); 1 {A,B,C} (rep A, r 400); 2 {D,E} (rep D, r 400);
// 3 {A,B} (rep A, r 337.464); 4 C; 5 D; 6 E; 7 A; 8 B.
LightTree thesis_tree();

// Orders the lights along a Morton curve (positions, or directions for
// directional lights), pairs neighbours level by level (an odd node is
// carried up), picks each representative with probability proportional to
// brightness (drawn from `seed`), and computes the cluster attributes the
// way SPEC §4 defines them, rounding radii and cones outwards to float.
LightTree morton_pairing_tree(const std::vector<SceneLight>& lights, uint64_t seed);

// Builds a tree over `lights` by hand: pairs neighbours level by level in index
// order (an odd node is carried up), the representative is the left child's,
// intensity sums, and the influence radius encloses the children's spheres
// (unbounded when a child is). Lights of different types are joined only by
// a mixed_types junction at the top.
LightTree make_pairing_tree(const std::vector<SceneLight>& lights);

// `tree` as the CPU evaluator and the renderer walk it (make_walk_tree); a
// test failure, and an empty tree, when it is malformed.
WalkTree walk_tree(const LightTree& tree);

bool finite3(const glm::dvec3& v);

double max_channel(const glm::dvec3& v);

// Channel by channel, within `rel` x |expected| + `abs`.
void expect_near_rel(const glm::dvec3& actual, const glm::dvec3& expected, double rel, double abs = 0.0);

// The bound criterion's guarantee: every cut node's error is at most its bound,
// which is at most error_ratio x the total estimate (largest channel).
void expect_within_cut_error(const CutResult& r, const glm::dvec3& exact, double ratio);

}  // namespace lc::test

#pragma once
// The paper's builder (Walter et al. 2005, section 4): greedy bottom-up, always
// merging the pair that makes the smallest cluster under the cluster metric
// (lightmass_server/builders/cluster_metric.h). Made fast by locally-ordered clustering
// (Walter et al. 2008): two clusters that are each other's best partner can be
// merged at once, in any order, and give the greedy result (up to ties) because
// the metric never decreases when a cluster grows. Each round finds best
// partners for the clusters that need one (in parallel, branch and bound on a
// cluster BVH) and merges every mutual pair. With orientation cones the union
// cone is not exactly monotone, so spot trees may differ slightly from greedy.
#include <cstdint>
#include <span>

#include "lightcuts/tree/build_tree.h"
#include "lightmass_server/builders/cluster_metric.h"
#include "lightmass_server/builders/tree_builder.h"
#include "lightcuts/result.h"

namespace lc::bake {

// Builds the tree over `leaves` (arena indices of leaves of one light type, in
// input order); returns the root's arena index (kNoChild when empty).
Result<int32_t> build_agglomerative_tree(BuildArena& arena, std::span<const uint32_t> leaves,
                                         const BuildOptions& options,
                                         const BuildProgressFn& progress, BuildReport& report);

// The textbook greedy, O(n^2) time: after every merge, the globally smallest
// pair. The reference the fast builder is tested against (small n only).
Result<int32_t> build_agglomerative_tree_exact_greedy(BuildArena& arena,
                                                      std::span<const uint32_t> leaves,
                                                      const BuildOptions& options);

// The metric's constants for these leaves: c = diagonal of their bounding box
// for spot lights (0 otherwise), and the intensity floor.
MetricParams agglomerative_metric_params(const BuildArena& arena, std::span<const uint32_t> leaves);

// Sum over the clusters of the subtree of the metric of merging their two
// children: what the greedy builder keeps small. Iterative.
double total_cluster_metric(const BuildArena& arena, int32_t root, const MetricParams& params);

}  // namespace lc::bake

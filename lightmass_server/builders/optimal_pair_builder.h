#pragma once
// The thesis's builder: level by level, pair the level's nodes so the sum of
// distances between paired representatives is minimal (exactly, by minimum-
// weight perfect matching), an odd level carrying one node up unpaired.
#include <cstdint>
#include <span>

#include "lightcuts/tree/build_tree.h"
#include "lightmass_server/builders/tree_builder.h"
#include "lightcuts/result.h"

namespace lc::bake {

// Builds the tree over `leaves` (arena indices of leaves of one light type, in
// input order) and returns its root's arena index (kNoChild when empty).
// Adds pairing cost, lower bound, exactness, level count and warnings to `report`.
// The next level is ordered by each node's smallest input light index; within a
// pair the left child is the one with the smaller such index.
Result<int32_t> build_optimal_pair_tree(BuildArena& arena, std::span<const uint32_t> leaves,
                                        const BuildOptions& options,
                                        const BuildProgressFn& progress, BuildReport& report);

}  // namespace lc::bake

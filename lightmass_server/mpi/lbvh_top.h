#pragma once
// Rank 0's part of a split LBVH (mpi/rank/split_lbvh.h): the top of the tree over the
// ranks' units (lbvh_units.h), and where every node goes. The top's splits
// are the one-process splits, found on the units' first and last codes (a
// split never cuts a unit: a unit is a node); the groups' roots are joined
// under junctions as build_light_tree joins them. Exported indices: the
// breadth-first order is, at every depth, the nodes in depth-first order
// (left child first), so walking the top depth first and giving each unit
// its next places at every depth it spans numbers every node as
// export_light_tree would, from the units' nodes-per-depth alone.
#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/tree/build_tree.h"
#include "lightcuts/result.h"
#include "lightmass_server/mpi/lbvh_units.h"
#include "lightmass_server/builders/tree_builder.h"

namespace lc::bake {

struct LbvhTop {
    // The top's nodes; children are 'unit u' (u + units) or 'top node t'
    // (t + 2 * units), representatives are unit numbers.
    std::vector<BuildNode> nodes;
    std::vector<SceneLight> representatives;  // each unit's root's representative light
    std::vector<int32_t> top_index;           // each top node's exported index
    // Each unit's exported index of its first node at each depth below its
    // root: unit u's are bases[base_at[u] .. base_at[u + 1]).
    std::vector<uint32_t> bases;
    std::vector<size_t> base_at;
    uint32_t unit_count = 0, node_count = 0, depth = 0;
};

// `units` in the global order (rank 0's, then rank 1's, ...); `level_counts`
// their nodes per depth, concatenated in that order.
Result<LbvhTop> build_lbvh_top(std::span<const UnitSummary> units, std::span<const uint32_t> level_counts,
                               const BuildOptions& options);

// Writes the top's records; `unit_representatives` holds the exported index
// of each unit's root's representative leaf (its rank wrote it).
Status write_top_records(int fd, const LbvhTop& top, std::span<const int32_t> unit_representatives);

}  // namespace lc::bake

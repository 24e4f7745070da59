#pragma once
// A rank's part of a split LBVH (mpi/rank/split_lbvh.h): the largest subtrees of the
// one-process tree that lie wholly within the rank's sorted share (its
// "units"), merged here, and their records written at the exported indices
// rank 0 hands out. A node of the rank's own split hierarchy is a node of the
// global tree when no key outside the share has its code prefix (only the
// share's first and last keys' neighbours can), so a rank needs its
// neighbours' boundary keys and nothing else; below such a node every split
// is the global one (a range's splits depend on its keys alone).
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/tree/build_tree.h"
#include "lightcuts/tree/light_tree.h"
#include "lightcuts/result.h"
#include "lightmass_server/builders/lbvh_builder.h"
#include "lightmass_server/builders/tree_builder.h"

namespace lc::bake {

// A rank's share of the lights, sorted by (group, code, leaf): a contiguous
// range of the one-process build's sort (mpi/rank/morton_partition.h).
struct SortedShare {
    std::vector<LbvhKey> keys;       // leaf: the global input index
    std::vector<SceneLight> lights;  // lights[k] is keys[k]'s
    // Group g's keys are [group_begin[g], group_begin[g + 1]).
    std::array<uint32_t, kLightGroupCount + 1> group_begin{};
    uint64_t total_lights = 0;  // over every rank
};

// The nearest other ranks' keys next to this share (absent: no such rank has a key).
struct ShareNeighbours {
    bool has_before = false, has_after = false;
    uint32_t before_group = 0, after_group = 0;
    uint64_t before_code = 0, after_code = 0;
};

// A unit: share keys [begin, end) of one group, merged. `inner` holds its
// inner nodes as merge_lbvh_subtree returns them (empty for a single light).
struct LbvhUnit {
    uint32_t group = 0, begin = 0, end = 0;
    std::vector<BuildNode> inner;
    std::vector<uint32_t> level_counts;  // nodes at each depth below the unit's root
};

// What rank 0 builds the top from: one per unit, trivially copyable.
struct UnitSummary {
    BuildNode root;             // global light indices
    SceneLight representative;  // the root's representative light
    uint64_t first_code = 0, last_code = 0;
    uint32_t group = 0, keys = 0, levels = 0, padding = 0;
};

// The units in the share's order (the global order), merged; none larger
// than `max_keys` lights (a split only adds units to the top).
Result<std::vector<LbvhUnit>> merge_units(const SortedShare& share, const ShareNeighbours& neighbours,
                                          uint32_t max_keys, const BuildOptions& options);
UnitSummary summarize_unit(const SortedShare& share, const LbvhUnit& unit);

// Writes the unit's records into the result channel file `fd`: the nodes at
// depth l below its root from exported index bases[l] on. Returns the
// exported index of its root's representative leaf.
Result<int32_t> write_unit_records(int fd, const SortedShare& share, const LbvhUnit& unit,
                                   std::span<const uint32_t> bases);

// Writes `chunk`'s nodes as the records of exported indices first, first + 1, ...
Status write_records_at(int fd, uint64_t first, const LightTree& chunk);

}  // namespace lc::bake

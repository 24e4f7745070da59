#include "lightmass_server/mpi/lbvh_units.h"

#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <cstring>
#include <string>

#include "lightcuts/tree/tree_export.h"
#include "protocol/channel_records.h"

namespace lc::bake {
namespace {

constexpr size_t kRecordsPerWrite = 4096;

struct KeyRange {
    uint32_t begin, end;
};

// Whether a key outside the share, next to it, has the range's code prefix
// (then the range is not a node of the global tree).
bool prefix_reaches_outside(const SortedShare& share, const ShareNeighbours& near, uint32_t group,
                            KeyRange r) {
    const uint64_t first = share.keys[r.begin].code;
    const uint64_t last = share.keys[r.end - 1].code;
    const int prefix = std::countl_zero(first ^ last);  // 64 when equal: the whole code
    const auto has_prefix = [&](uint64_t code) { return std::countl_zero(code ^ first) >= prefix; };
    const bool before =
        r.begin == 0 && near.has_before && near.before_group == group && has_prefix(near.before_code);
    const bool after = r.end == share.keys.size() && near.has_after && near.after_group == group &&
                       has_prefix(near.after_code);
    return before || after;
}

// The units' key ranges in Morton order: the global nodes within the share
// that are no larger than max_keys, or single lights where equal codes run
// past the share (their local middle splits are not the global ones).
std::vector<std::pair<uint32_t, KeyRange>> unit_ranges(const SortedShare& share, const ShareNeighbours& near,
                                                       uint32_t max_keys) {
    std::vector<std::pair<uint32_t, KeyRange>> units;
    for (uint32_t g = 0; g < kLightGroupCount; ++g) {
        if (share.group_begin[g] == share.group_begin[g + 1]) continue;
        std::vector<KeyRange> stack{{share.group_begin[g], share.group_begin[g + 1]}};
        while (!stack.empty()) {
            const KeyRange r = stack.back();
            stack.pop_back();
            const bool outside = r.end - r.begin > 1 && prefix_reaches_outside(share, near, g, r);
            if (r.end - r.begin == 1 || (!outside && r.end - r.begin <= max_keys)) {
                units.push_back({g, r});
            } else if (outside && share.keys[r.begin].code == share.keys[r.end - 1].code) {
                for (uint32_t k = r.begin; k < r.end; ++k) units.push_back({g, KeyRange{k, k + 1}});
            } else {
                const uint32_t split = lbvh_split_position(share.keys, r.begin, r.end);
                stack.push_back({split, r.end});
                stack.push_back({r.begin, split});
            }
        }
    }
    return units;
}

// A unit's leaves by global light index: (index, key offset in the unit).
class UnitLeaves {
public:
    UnitLeaves(const SortedShare& share, const LbvhUnit& unit) {
        for (uint32_t k = unit.begin; k < unit.end; ++k)
            by_index_.push_back({share.keys[k].leaf, k - unit.begin});
        std::sort(by_index_.begin(), by_index_.end());
    }
    // The key offset of leaf `index`, or -1 when it is not in the unit.
    int64_t offset_of(uint32_t index) const {
        const auto at =
            std::lower_bound(by_index_.begin(), by_index_.end(), std::pair<uint32_t, uint32_t>{index, 0});
        return at != by_index_.end() && at->first == index ? int64_t(at->second) : -1;
    }

private:
    std::vector<std::pair<uint32_t, uint32_t>> by_index_;
};

// The unit's nodes level by level from its root, as exported (left child
// first): >= 0 a leaf (its key offset in the unit with `leaves`, else its
// global light index), <= -2 an inner ordinal.
Result<std::vector<std::vector<int32_t>>> unit_levels(const SortedShare& share, const LbvhUnit& unit,
                                                      const UnitLeaves* leaves) {
    std::vector<std::vector<int32_t>> levels;
    levels.push_back(
        {unit.inner.empty() ? (leaves ? 0 : int32_t(share.keys[unit.begin].leaf)) : encode_inner_child(0)});
    for (;;) {
        std::vector<int32_t> next;
        for (int32_t ref : levels.back()) {
            if (ref >= 0) continue;
            const BuildNode& node = unit.inner[size_t(-2 - ref)];
            for (int32_t child : {node.left, node.right}) {
                const int64_t leaf = child >= 0 && leaves ? leaves->offset_of(uint32_t(child)) : child;
                if (leaf < 0 && child >= 0) return make_error("a unit's node names a light outside it");
                if (child != kNoChild) next.push_back(int32_t(leaf));
            }
        }
        if (next.empty()) return levels;
        levels.push_back(std::move(next));
    }
}

}  // namespace

Result<std::vector<LbvhUnit>> merge_units(const SortedShare& share, const ShareNeighbours& neighbours,
                                          uint32_t max_keys, const BuildOptions& options) {
    std::vector<LbvhUnit> units;
    for (const auto& [group, range] : unit_ranges(share, neighbours, std::max<uint32_t>(2, max_keys))) {
        LbvhUnit unit{group, range.begin, range.end, {}, {}};
        if (range.end - range.begin > 1) {
            const size_t n = range.end - range.begin;
            Result<std::vector<BuildNode>> merged =
                merge_lbvh_subtree(std::span(share.keys).subspan(range.begin, n),
                                   std::span(share.lights).subspan(range.begin, n), options);
            if (!merged) return merged.failure();
            unit.inner = std::move(merged.value());
        }
        Result<std::vector<std::vector<int32_t>>> levels = unit_levels(share, unit, nullptr);
        if (!levels) return levels.failure();
        for (const std::vector<int32_t>& level : *levels) unit.level_counts.push_back(uint32_t(level.size()));
        units.push_back(std::move(unit));
    }
    return units;
}

UnitSummary summarize_unit(const SortedShare& share, const LbvhUnit& unit) {
    UnitSummary summary;
    const uint32_t first_leaf = share.keys[unit.begin].leaf;
    summary.root = unit.inner.empty() ? make_leaf(share.lights[unit.begin], first_leaf) : unit.inner[0];
    for (uint32_t k = unit.begin; k < unit.end; ++k)
        if (share.keys[k].leaf == summary.root.representative) summary.representative = share.lights[k];
    summary.first_code = share.keys[unit.begin].code;
    summary.last_code = share.keys[unit.end - 1].code;
    summary.group = unit.group;
    summary.keys = unit.end - unit.begin;
    summary.levels = uint32_t(unit.level_counts.size());
    return summary;
}

Result<int32_t> write_unit_records(int fd, const SortedShare& share, const LbvhUnit& unit,
                                   std::span<const uint32_t> bases) {
    const UnitLeaves leaves(share, unit);
    Result<std::vector<std::vector<int32_t>>> levels = unit_levels(share, unit, &leaves);
    if (!levels) return levels.failure();
    if (bases.size() != levels->size()) return make_error("rank 0 sent a unit the wrong number of depths");
    std::vector<int32_t> leaf_index(unit.end - unit.begin, -1);  // exported, by key offset
    for (size_t l = 0; l < levels->size(); ++l)
        for (size_t j = 0; j < (*levels)[l].size(); ++j)
            if ((*levels)[l][j] >= 0) leaf_index[size_t((*levels)[l][j])] = int32_t(bases[l] + j);
    const auto representative_of = [&](const BuildNode& node) {
        return leaves.offset_of(node.representative);
    };
    LightTree chunk;
    for (size_t l = 0; l < levels->size(); ++l) {
        // Children sit side by side in the next depth, in this depth's order.
        uint32_t next_child = l + 1 < levels->size() ? bases[l + 1] : 0;
        for (size_t j = 0; j < (*levels)[l].size(); ++j) {
            const int32_t ref = (*levels)[l][j];
            if (ref >= 0) {
                const SceneLight& light = share.lights[unit.begin + size_t(ref)];
                const BuildNode leaf = make_leaf(light, share.keys[unit.begin + size_t(ref)].leaf);
                chunk.nodes.push_back(export_node(leaf, light, kNoChild, int32_t(bases[l] + j)));
            } else {
                const BuildNode& node = unit.inner[size_t(-2 - ref)];
                const int64_t representative = representative_of(node);
                if (representative < 0) return make_error("a unit's representative is outside it");
                chunk.nodes.push_back(export_node(node, share.lights[unit.begin + size_t(representative)],
                                                  int32_t(next_child), leaf_index[size_t(representative)]));
                next_child += uint32_t(node.left != kNoChild) + uint32_t(node.right != kNoChild);
            }
            if (chunk.nodes.size() == kRecordsPerWrite || j + 1 == (*levels)[l].size()) {
                const uint64_t first = bases[l] + j + 1 - chunk.nodes.size();
                if (Status written = write_records_at(fd, first, chunk); !written) return written.failure();
                chunk.nodes.clear();
            }
        }
    }
    if (unit.inner.empty()) return int32_t(bases[0]);
    const int64_t root_representative = representative_of(unit.inner[0]);
    return root_representative < 0 ? -1 : leaf_index[size_t(root_representative)];
}

Status write_records_at(int fd, uint64_t first, const LightTree& chunk) {
    std::vector<uint8_t> bytes(chunk.nodes.size() * result_record_bytes());
    write_result_records(chunk, 0, chunk.nodes.size(), bytes);
    const uint64_t offset = 4 + first * result_record_bytes();
    for (size_t done = 0; done < bytes.size();) {
        const ssize_t wrote = ::pwrite(fd, bytes.data() + done, bytes.size() - done, off_t(offset + done));
        if (wrote < 0 && errno == EINTR) continue;
        if (wrote <= 0)
            return make_error(std::string("cannot write the tree's records: ") + std::strerror(errno));
        done += size_t(wrote);
    }
    return Ok{};
}

}  // namespace lc::bake

#include "lightmass_server/mpi/lbvh_top.h"

#include <algorithm>
#include <bit>
#include <string>
#include <utility>

#include "lightcuts/status_macros.h"
#include "lightcuts/tree/tree_export.h"
#include "lightmass_server/builders/cluster_attributes.h"
#include "protocol/channel_records.h"

namespace lc::bake {
namespace {

// The merges over the units: an arena whose "leaves" are never read (every
// unit root is a node, so merges compare the roots' global smallest light
// indices), whose lights are the units' representative lights.
class TopBuilder {
public:
    TopBuilder(std::span<const UnitSummary> units, const BuildOptions& options)
        : units_(units), options_(options) {
        for (const UnitSummary& unit : units) lights_.push_back(unit.representative);
        arena_.lights = lights_;
        arena_.nodes.resize(units.size());  // the unread leaf slots
        for (size_t u = 0; u < units.size(); ++u) {
            BuildNode root = units[u].root;
            root.representative = uint32_t(u);
            arena_.nodes.push_back(root);
        }
    }

    // The tree over units [i, j) of one group: split as the one-process build
    // splits their keys. Returns its arena index.
    Result<uint32_t> join(size_t i, size_t j) {
        const size_t unit_count = units_.size();
        if (j - i == 1) return uint32_t(unit_count + i);
        Result<size_t> split = split_between(i, j);
        if (!split) return split.failure();
        Result<uint32_t> left = join(i, *split);
        if (!left) return left;
        Result<uint32_t> right = join(*split, j);
        if (!right) return right;
        arena_.nodes.push_back(
            merge_clusters(arena_, *left, *right, options_.representative_rule, options_.seed));
        return uint32_t(arena_.nodes.size() - 1);
    }

    uint32_t junction(uint32_t left, uint32_t right) {
        arena_.nodes.push_back(make_junction(arena_, left, right));
        return uint32_t(arena_.nodes.size() - 1);
    }

    const BuildArena& arena() const { return arena_; }
    std::vector<SceneLight> take_lights() { return std::move(lights_); }

private:
    // The first unit of the right child: where the highest differing bit of
    // the range's codes turns on, or the middle light when they are all equal.
    Result<size_t> split_between(size_t i, size_t j) const {
        const uint64_t first = units_[i].first_code, last = units_[j - 1].last_code;
        size_t k = i + 1;
        if (first != last) {
            const int bit = 63 - std::countl_zero(first ^ last);
            while (k < j && ((units_[k].first_code >> bit) & 1) == 0) ++k;
            if (k < j && ((units_[k - 1].last_code >> bit) & 1) == 0) return k;
        } else {
            uint64_t total = 0, before = units_[i].keys;
            for (size_t u = i; u < j; ++u) total += units_[u].keys;
            while (k < j && before < total / 2) before += units_[k++].keys;
            if (k < j && before == total / 2) return k;
        }
        return make_error("the ranks' subtrees straddle a split of the tree (units " + std::to_string(i) +
                          " to " + std::to_string(j) + ")");
    }

    std::span<const UnitSummary> units_;
    const BuildOptions& options_;
    std::vector<SceneLight> lights_;
    BuildArena arena_;
};

// The top over every group's units, the groups joined left to right. Returns the root's arena index.
Result<uint32_t> build_top_nodes(std::span<const UnitSummary> units, TopBuilder& builder) {
    std::vector<uint32_t> roots;
    for (size_t i = 0; i < units.size();) {
        size_t j = i + 1;
        while (j < units.size() && units[j].group == units[i].group) ++j;
        if (units[j - 1].group < units[i].group)
            return make_error("the ranks' subtrees are not in group order");
        Result<uint32_t> root = builder.join(i, j);
        if (!root) return root;
        roots.push_back(*root);
        i = j;
    }
    uint32_t root = roots[0];
    for (size_t g = 1; g < roots.size(); ++g) root = builder.junction(root, roots[g]);
    return root;
}

// Depth-first (left child first) from the root: each arena index with its depth.
std::vector<std::pair<uint32_t, uint32_t>> depth_first(const BuildArena& arena, uint32_t root,
                                                       size_t unit_count) {
    std::vector<std::pair<uint32_t, uint32_t>> order, stack{{root, 0}};
    while (!stack.empty()) {
        const auto [index, depth] = stack.back();
        stack.pop_back();
        order.push_back({index, depth});
        if (index < 2 * unit_count) continue;  // a unit: its own rank walks it
        const BuildNode& node = arena.nodes[index];
        stack.push_back({uint32_t(node.right), depth + 1});
        stack.push_back({uint32_t(node.left), depth + 1});
    }
    return order;
}

}  // namespace

Result<LbvhTop> build_lbvh_top(std::span<const UnitSummary> units, std::span<const uint32_t> level_counts,
                               const BuildOptions& options) {
    LbvhTop top;
    const size_t unit_count = units.size();
    top.unit_count = uint32_t(unit_count);
    if (units.empty()) return top;
    top.base_at.push_back(0);
    for (const UnitSummary& unit : units) top.base_at.push_back(top.base_at.back() + unit.levels);
    if (top.base_at.back() != level_counts.size())
        return make_error("the ranks sent the wrong number of depths");
    TopBuilder builder(units, options);
    Result<uint32_t> root = build_top_nodes(units, builder);
    if (!root) return root.failure();
    const std::vector<std::pair<uint32_t, uint32_t>> order = depth_first(builder.arena(), *root, unit_count);
    // Nodes per depth, then each depth's first index, then the places in depth-first order.
    std::vector<uint64_t> at_depth;
    const auto each_depth = [&](uint32_t index, uint32_t depth, auto&& take) {
        if (index >= 2 * unit_count) return take(depth, 1u, size_t(-1));
        const size_t u = index - unit_count;
        for (size_t l = 0; l < units[u].levels; ++l)
            take(depth + uint32_t(l), level_counts[top.base_at[u] + l], top.base_at[u] + l);
    };
    for (const auto& [index, depth] : order)
        each_depth(index, depth, [&](uint32_t d, uint32_t count, size_t) {
            if (at_depth.size() <= d) at_depth.resize(d + 1, 0);
            at_depth[d] += count;
        });
    uint64_t total = 0;
    for (uint64_t& count : at_depth) total += std::exchange(count, total);  // now each depth's first index
    if (total > kMaxTreeNodes) return make_error("too large: " + std::to_string(total) + " tree nodes");
    top.node_count = uint32_t(total);
    top.depth = uint32_t(at_depth.size() - 1);
    top.bases.resize(level_counts.size());
    top.nodes.assign(builder.arena().nodes.begin() + ptrdiff_t(2 * unit_count), builder.arena().nodes.end());
    top.top_index.resize(top.nodes.size());
    for (const auto& [index, depth] : order)
        each_depth(index, depth, [&](uint32_t d, uint32_t count, size_t base) {
            if (base != size_t(-1))
                top.bases[base] = uint32_t(at_depth[d]);
            else
                top.top_index[index - 2 * unit_count] = int32_t(at_depth[d]);
            at_depth[d] += count;
        });
    top.representatives = builder.take_lights();
    return top;
}

Status write_top_records(int fd, const LbvhTop& top, std::span<const int32_t> unit_representatives) {
    const size_t units = top.unit_count;
    if (unit_representatives.size() != units)
        return make_error("the ranks sent the wrong number of representatives");
    const auto index_of = [&](int32_t child) {
        const size_t c = size_t(child);
        return c >= 2 * units ? top.top_index[c - 2 * units] : int32_t(top.bases[top.base_at[c - units]]);
    };
    LightTree one;
    one.nodes.resize(1);
    for (size_t t = 0; t < top.nodes.size(); ++t) {
        const BuildNode& node = top.nodes[t];
        const int32_t left = index_of(node.left);
        if (index_of(node.right) != left + 1) return make_error("the top's children are not side by side");
        one.nodes[0] = export_node(node, top.representatives[node.representative], left,
                                   unit_representatives[node.representative]);
        LC_RETURN_IF_ERROR(write_records_at(fd, uint64_t(top.top_index[t]), one));
    }
    return Ok{};
}

}  // namespace lc::bake

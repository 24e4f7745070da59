#include "lightmass_server/builders/lbvh_builder.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <tbb/parallel_sort.h>
#include <glm/common.hpp>

#include <algorithm>
#include <bit>
#include <limits>
#include <string>
#include <vector>

#include "lightcuts/status_macros.h"
#include "lightmass_server/builders/build_phase_timer.h"
#include "lightmass_server/builders/cluster_attributes.h"

namespace lc::bake {
namespace {

constexpr int kBitsPerAxis = 21;  // 63-bit codes

// Spreads the low 21 bits of v so that two zero bits follow each bit.
uint64_t spread_bits(uint64_t v) {
    v &= 0x1FFFFFu;
    v = (v | (v << 32)) & 0x001F00000000FFFFull;
    v = (v | (v << 16)) & 0x001F0000FF0000FFull;
    v = (v | (v << 8)) & 0x100F00F00F00F00Full;
    v = (v | (v << 4)) & 0x10C30C30C30C30C3ull;
    v = (v | (v << 2)) & 0x1249249249249249ull;
    return v;
}

uint64_t morton_code(const glm::dvec3& p, const glm::dvec3& lo, const glm::dvec3& scale) {
    constexpr double kMax = double((1u << kBitsPerAxis) - 1);
    const glm::dvec3 q = glm::clamp((p - lo) * scale, glm::dvec3(0.0), glm::dvec3(kMax));
    return (spread_bits(uint64_t(q.x)) << 2) | (spread_bits(uint64_t(q.y)) << 1) |
           spread_bits(uint64_t(q.z));
}

using Keyed = LbvhKey;

// A node of the split hierarchy over the sorted range [begin, end).
struct SplitNode {
    uint32_t begin, end;
    int32_t left = -1, right = -1;
};

uint32_t split_position(const std::vector<Keyed>& keys, uint32_t begin, uint32_t end) {
    return lbvh_split_position(keys, begin, end);
}

// Leaves sit in input order, far from their Morton neighbours, so the lowest
// merges read the arena at random: ask for a node's children this many nodes
// ahead, and for their representatives' lights (the radius reads them) half as
// far ahead, once the children have arrived.
constexpr size_t kPrefetchAhead = 16;

void prefetch_children(const BuildArena& arena, const SplitNode& node,
                       const std::vector<uint32_t>& arena_of) {
    if (node.left < 0) return;
    prefetch_merge_input(arena, arena_of[size_t(node.left)]);
    prefetch_merge_input(arena, arena_of[size_t(node.right)]);
}

void prefetch_children_lights(const BuildArena& arena, const SplitNode& node,
                              const std::vector<uint32_t>& arena_of) {
    if (node.left < 0) return;
    prefetch_representative_lights(arena, arena_of[size_t(node.left)], arena_of[size_t(node.right)]);
}


// The split hierarchy over sorted keys: nodes numbered breadth-first, depth d
// holding nodes [depth_begin[d], depth_begin[d + 1]).
struct SplitHierarchy {
    std::vector<SplitNode> nodes;
    std::vector<size_t> depth_begin{0};
};

// Top-down splits, one depth at a time: the ranges of one depth are disjoint,
// so their split positions are searched in parallel; the children are then
// appended in order, parents before children (breadth-first, as a serial work
// list would number them). A range's splits depend on its keys alone, so a
// subtree's hierarchy is the same built alone (merge_lbvh_subtree).
SplitHierarchy split_hierarchy(const std::vector<Keyed>& keys) {
    SplitHierarchy h;
    std::vector<SplitNode>& nodes = h.nodes;
    nodes.reserve(2 * keys.size());
    nodes.push_back(SplitNode{0, uint32_t(keys.size())});
    std::vector<uint32_t> split_at;
    while (h.depth_begin.back() < nodes.size()) {
        const size_t begin = h.depth_begin.back();
        const size_t end = nodes.size();
        split_at.resize(end - begin);
        tbb::parallel_for(
            tbb::blocked_range<size_t>(begin, end, 1024), [&](const tbb::blocked_range<size_t>& range) {
                for (size_t i = range.begin(); i != range.end(); ++i) {
                    const SplitNode& node = nodes[i];
                    // 0 marks a leaf: a split always lies after its range's first key.
                    split_at[i - begin] =
                        node.end - node.begin < 2 ? 0 : split_position(keys, node.begin, node.end);
                }
            });
        for (size_t i = begin; i < end; ++i) {
            const uint32_t split = split_at[i - begin];
            if (split == 0) continue;
            const uint32_t range_begin = nodes[i].begin;
            const uint32_t range_end = nodes[i].end;
            nodes[i].left = int32_t(nodes.size());
            nodes.push_back(SplitNode{range_begin, split});
            nodes[i].right = int32_t(nodes.size());
            nodes.push_back(SplitNode{split, range_end});
        }
        h.depth_begin.push_back(end);
    }
    return h;
}

// Arena slots fixed in advance (the i-th split node from the end takes the
// i-th slot after the arena's nodes), which makes the arena the same at any
// thread count; leaves are their lights' slots.
std::vector<uint32_t> assign_arena_slots(BuildArena& arena, const SplitHierarchy& h, const std::vector<Keyed>& keys) {
    std::vector<uint32_t> arena_of(h.nodes.size());
    size_t slot = arena.nodes.size();
    for (size_t i = h.nodes.size(); i-- > 0;) {
        arena_of[i] = h.nodes[i].left < 0 ? keys[h.nodes[i].begin].leaf : uint32_t(slot++);
    }
    arena.nodes.resize(slot);
    return arena_of;
}

// Bottom-up cluster attributes, one depth at a time from the deepest: the
// merges of one depth are independent, so they run in parallel.
Status merge_bottom_up(BuildArena& arena, const SplitHierarchy& h, const std::vector<uint32_t>& arena_of,
                       const BuildOptions& options, const BuildProgressFn& progress, size_t& merges) {
    const size_t total_merges = (h.nodes.size() - 1) / 2;
    for (size_t d = h.depth_begin.size() - 1; d-- > 0;) {
        tbb::parallel_for(tbb::blocked_range<size_t>(h.depth_begin[d], h.depth_begin[d + 1], 4096),
                          [&](const tbb::blocked_range<size_t>& range) {
                              for (size_t i = range.begin(); i != range.end(); ++i) {
                                  if (i + kPrefetchAhead < range.end())
                                      prefetch_children(arena, h.nodes[i + kPrefetchAhead], arena_of);
                                  if (i + kPrefetchAhead / 2 < range.end())
                                      prefetch_children_lights(arena, h.nodes[i + kPrefetchAhead / 2], arena_of);
                                  const SplitNode& node = h.nodes[i];
                                  if (node.left < 0) continue;
                                  arena.nodes[arena_of[i]] = merge_clusters(
                                      arena, arena_of[size_t(node.left)], arena_of[size_t(node.right)],
                                      options.representative_rule, options.seed);
                              }
                          });
        const size_t children = d + 2 < h.depth_begin.size() ? h.depth_begin[d + 2] - h.depth_begin[d + 1] : 0;
        merges = std::min(total_merges, merges + children / 2);
        if (progress && !progress(double(merges) / double(std::max<size_t>(1, total_merges)))) {
            return make_error("cancelled during the lbvh build (" + std::to_string(merges) + " of " +
                                  std::to_string(total_merges) + " merges done)",
                              ErrorKind::kCancelled);
        }
    }
    return Ok{};
}

// The inner split nodes of the subtree under `root`, breadth-first.
std::vector<uint32_t> inner_nodes_below(const SplitHierarchy& h, uint32_t root) {
    std::vector<uint32_t> inner{root};
    for (size_t k = 0; k < inner.size(); ++k) {
        const SplitNode& node = h.nodes[inner[k]];
        for (int32_t child : {node.left, node.right})
            if (h.nodes[size_t(child)].left >= 0) inner.push_back(uint32_t(child));
    }
    return inner;
}

}  // namespace

Result<int32_t> build_lbvh_tree(BuildArena& arena, std::span<const uint32_t> leaves,
                                const BuildOptions& options, const BuildProgressFn& progress,
                                BuildReport& report) {
    if (leaves.empty()) return kNoChild;
    if (leaves.size() == 1) return int32_t(leaves[0]);
    BuildPhaseTimer timer(report);

    // A leaf is its own representative: its point comes straight from its light.
    const auto point_of = [&](uint32_t leaf) { return light_point(arena.lights[leaf]); };
    struct Bounds {
        glm::dvec3 lo{std::numeric_limits<double>::max()};
        glm::dvec3 hi{std::numeric_limits<double>::lowest()};
    };
    // min and max are exact, so the reduction's order cannot change the bounds.
    const Bounds bounds = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, leaves.size(), 1u << 14), Bounds{},
        [&](const tbb::blocked_range<size_t>& range, Bounds b) {
            for (size_t i = range.begin(); i != range.end(); ++i) {
                const glm::dvec3 p = point_of(leaves[i]);
                b.lo = glm::min(b.lo, p);
                b.hi = glm::max(b.hi, p);
            }
            return b;
        },
        [](const Bounds& a, const Bounds& b) {
            return Bounds{glm::min(a.lo, b.lo), glm::max(a.hi, b.hi)};
        });
    const LbvhCurve curve = lbvh_curve(bounds.lo, bounds.hi);

    std::vector<Keyed> keys(leaves.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, leaves.size(), 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t i = range.begin(); i != range.end(); ++i) {
                              keys[i] = Keyed{lbvh_code(arena.lights[leaves[i]], curve), leaves[i]};
                          }
                      });
    timer.lap("lbvh: bounds and Morton codes");
    tbb::parallel_sort(keys.begin(), keys.end());  // a strict total order: deterministic
    timer.lap("lbvh: sort");

    const SplitHierarchy hierarchy = split_hierarchy(keys);
    const std::vector<uint32_t> arena_of = assign_arena_slots(arena, hierarchy, keys);
    timer.lap("lbvh: splits");
    size_t merges = 0;
    LC_RETURN_IF_ERROR(merge_bottom_up(arena, hierarchy, arena_of, options, progress, merges));
    timer.lap("lbvh: cluster attributes");
    return int32_t(arena_of[0]);
}

}  // namespace lc::bake

namespace lc::bake {

LbvhCurve lbvh_curve(const glm::dvec3& lo, const glm::dvec3& hi) {
    const glm::dvec3 size = hi - lo;
    const double extent = std::max({size.x, size.y, size.z});
    const double cells = double((1u << kBitsPerAxis) - 1);
    return LbvhCurve{lo, glm::dvec3(extent > 0.0 ? cells / extent : 0.0)};
}

uint64_t lbvh_code(const SceneLight& light, const LbvhCurve& curve) {
    return morton_code(light_point(light), curve.lo, curve.scale);
}

uint32_t lbvh_split_position(std::span<const LbvhKey> keys, uint32_t begin, uint32_t end) {
    const uint64_t first = keys[begin].code;
    const uint64_t last = keys[end - 1].code;
    if (first == last) return begin + (end - begin) / 2;
    const int common_prefix = std::countl_zero(first ^ last);
    // Binary search for the first code that differs from `first` in that bit.
    uint32_t lo = begin, hi = end - 1;  // keys[lo] has the bit clear, keys[hi] set
    while (hi - lo > 1) {
        const uint32_t mid = lo + (hi - lo) / 2;
        if (std::countl_zero(first ^ keys[mid].code) > common_prefix) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    return hi;
}

Result<std::vector<BuildNode>> merge_lbvh_subtree(std::span<const LbvhKey> keys, std::span<const SceneLight> lights,
                                                  const BuildOptions& options) {
    if (keys.size() != lights.size() || keys.size() < 2) return make_error("a subtree needs 2 or more keys, one light each");
    // Local leaf indices in the order of the global ones: merges order children
    // by their smallest light index, so the local order must be the global one.
    std::vector<uint32_t> by_global(keys.size());
    for (uint32_t k = 0; k < keys.size(); ++k) by_global[k] = k;
    std::sort(by_global.begin(), by_global.end(), [&](uint32_t a, uint32_t b) { return keys[a].leaf < keys[b].leaf; });
    std::vector<SceneLight> local_lights(keys.size());
    std::vector<uint32_t> global_of(keys.size());
    std::vector<Keyed> local_keys(keys.size());
    for (uint32_t j = 0; j < by_global.size(); ++j) {
        const uint32_t k = by_global[j];
        local_lights[j] = lights[k];
        global_of[j] = keys[k].leaf;
        local_keys[k] = Keyed{keys[k].code, j};
    }
    BuildArena arena;
    arena.lights = local_lights;
    arena.nodes.resize(local_lights.size());
    const SplitHierarchy h = split_hierarchy(local_keys);
    const std::vector<uint32_t> arena_of = assign_arena_slots(arena, h, local_keys);
    size_t merges = 0;
    LC_RETURN_IF_ERROR(merge_bottom_up(arena, h, arena_of, options, {}, merges));
    // Breadth-first inner nodes, children as global light indices or inner ordinals.
    const std::vector<uint32_t> inner = inner_nodes_below(h, 0);
    std::vector<int32_t> ordinal_of_slot(arena.nodes.size(), kNoChild);
    for (size_t k = 0; k < inner.size(); ++k) ordinal_of_slot[arena_of[inner[k]]] = encode_inner_child(uint32_t(k));
    const auto global_child = [&](int32_t slot) {
        return arena.is_leaf_index(uint32_t(slot)) ? int32_t(global_of[size_t(slot)]) : ordinal_of_slot[size_t(slot)];
    };
    std::vector<BuildNode> out;
    out.reserve(inner.size());
    for (uint32_t i : inner) {
        BuildNode node = arena.nodes[arena_of[i]];
        node.left = global_child(node.left);
        node.right = global_child(node.right);
        node.representative = global_of[node.representative];
        node.min_light_index = global_of[node.min_light_index];
        out.push_back(node);
    }
    return out;
}

}  // namespace lc::bake

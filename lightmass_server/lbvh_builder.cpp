#include "lightmass_server/lbvh_builder.h"

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

#include "lightmass_server/build_phase_timer.h"
#include "lightmass_server/cluster_attributes.h"

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

struct Keyed {
    uint64_t code;
    uint32_t leaf;  // arena index == input light index: the tie-break
    bool operator<(const Keyed& o) const {
        return code < o.code || (code == o.code && leaf < o.leaf);
    }
};

// A node of the split hierarchy over the sorted range [begin, end).
struct SplitNode {
    uint32_t begin, end;
    int32_t left = -1, right = -1;
};

// Where [begin, end) splits: after the last code sharing the range's highest
// differing bit with the first; the middle when every code is equal.
uint32_t split_position(const std::vector<Keyed>& keys, uint32_t begin, uint32_t end) {
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

}  // namespace

Result<int32_t> build_lbvh_tree(BuildArena& arena, std::span<const uint32_t> leaves,
                                const BuildOptions& options, const BuildProgressFn& progress,
                                BuildReport& report) {
    if (leaves.empty()) return kNoBuildChild;
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
    // One scale for all axes keeps the curve's cells cubic.
    const glm::dvec3 size = bounds.hi - bounds.lo;
    const double extent = std::max({size.x, size.y, size.z});
    const double cells = double((1u << kBitsPerAxis) - 1);
    const glm::dvec3 scale(extent > 0.0 ? cells / extent : 0.0);

    std::vector<Keyed> keys(leaves.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, leaves.size(), 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t i = range.begin(); i != range.end(); ++i) {
                              keys[i] = Keyed{morton_code(point_of(leaves[i]), bounds.lo, scale), leaves[i]};
                          }
                      });
    timer.lap("lbvh: bounds and Morton codes");
    tbb::parallel_sort(keys.begin(), keys.end());  // a strict total order: deterministic
    timer.lap("lbvh: sort");

    // Top-down splits, one depth at a time: the ranges of one depth are
    // disjoint, so their split positions are searched in parallel; the children
    // are then appended in order, parents before children (breadth-first, as a
    // serial work list would number them).
    std::vector<SplitNode> nodes;
    nodes.reserve(2 * leaves.size());
    nodes.push_back(SplitNode{0, uint32_t(keys.size())});
    std::vector<size_t> depth_begin{0};  // depth d holds nodes [depth_begin[d], depth_begin[d + 1])
    std::vector<uint32_t> split_at;
    while (depth_begin.back() < nodes.size()) {
        const size_t begin = depth_begin.back();
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
        depth_begin.push_back(end);
    }

    // Bottom-up cluster attributes, one depth at a time from the deepest: the
    // merges of one depth are independent, so they run in parallel into arena
    // slots fixed in advance (the i-th split node from the end takes the i-th
    // slot), which makes the arena the same at any thread count.
    std::vector<uint32_t> arena_of(nodes.size());
    size_t slot = arena.nodes.size();
    for (size_t i = nodes.size(); i-- > 0;) {
        arena_of[i] = nodes[i].left < 0 ? keys[nodes[i].begin].leaf : uint32_t(slot++);
    }
    arena.nodes.resize(slot);
    timer.lap("lbvh: splits");

    const size_t total_merges = leaves.size() - 1;
    size_t merges = 0;
    for (size_t d = depth_begin.size() - 1; d-- > 0;) {
        tbb::parallel_for(tbb::blocked_range<size_t>(depth_begin[d], depth_begin[d + 1], 4096),
                          [&](const tbb::blocked_range<size_t>& range) {
                              for (size_t i = range.begin(); i != range.end(); ++i) {
                                  if (i + kPrefetchAhead < range.end())
                                      prefetch_children(arena, nodes[i + kPrefetchAhead], arena_of);
                                  if (i + kPrefetchAhead / 2 < range.end())
                                      prefetch_children_lights(arena, nodes[i + kPrefetchAhead / 2],
                                                               arena_of);
                                  const SplitNode& node = nodes[i];
                                  if (node.left < 0) continue;
                                  arena.nodes[arena_of[i]] = merge_clusters(
                                      arena, arena_of[size_t(node.left)], arena_of[size_t(node.right)],
                                      options.representative_rule, options.seed);
                              }
                          });
        const size_t children = d + 2 < depth_begin.size() ? depth_begin[d + 2] - depth_begin[d + 1] : 0;
        merges += children / 2;
        if (progress && !progress(double(merges) / double(total_merges))) {
            return make_error("cancelled during the lbvh build (" + std::to_string(merges) + " of " +
                                  std::to_string(total_merges) + " merges done)",
                              ErrorKind::kCancelled);
        }
    }
    timer.lap("lbvh: cluster attributes");
    return int32_t(arena_of[0]);
}

}  // namespace lc::bake

#include "lightmass_server/lbvh_builder.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <glm/common.hpp>

#include <algorithm>
#include <bit>
#include <limits>
#include <string>
#include <vector>

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

}  // namespace

Result<int32_t> build_lbvh_tree(BuildArena& arena, std::span<const uint32_t> leaves,
                                const BuildOptions& options, const BuildProgressFn& progress) {
    if (leaves.empty()) return kNoBuildChild;
    if (leaves.size() == 1) return int32_t(leaves[0]);

    glm::dvec3 lo(std::numeric_limits<double>::max());
    glm::dvec3 hi(std::numeric_limits<double>::lowest());
    for (const uint32_t leaf : leaves) {
        const glm::dvec3 p = representative_point(arena, arena.nodes[leaf]);
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    // One scale for all axes keeps the curve's cells cubic.
    const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
    const double cells = double((1u << kBitsPerAxis) - 1);
    const glm::dvec3 scale(extent > 0.0 ? cells / extent : 0.0);

    std::vector<Keyed> keys(leaves.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, leaves.size(), 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t i = range.begin(); i != range.end(); ++i) {
                              const glm::dvec3 p = representative_point(arena, arena.nodes[leaves[i]]);
                              keys[i] = Keyed{morton_code(p, lo, scale), leaves[i]};
                          }
                      });
    tbb::parallel_sort(keys.begin(), keys.end());  // a strict total order: deterministic

    // Top-down splits with a work list (no recursion), parents before children.
    std::vector<SplitNode> nodes;
    nodes.reserve(2 * leaves.size());
    nodes.push_back(SplitNode{0, uint32_t(keys.size())});
    for (size_t i = 0; i < nodes.size(); ++i) {
        const uint32_t begin = nodes[i].begin;
        const uint32_t end = nodes[i].end;
        if (end - begin < 2) continue;
        const uint32_t split = split_position(keys, begin, end);
        nodes[i].left = int32_t(nodes.size());
        nodes.push_back(SplitNode{begin, split});
        nodes[i].right = int32_t(nodes.size());
        nodes.push_back(SplitNode{split, end});
    }

    // Bottom-up cluster attributes, one depth at a time from the deepest: the
    // merges of one depth are independent, so they run in parallel into arena
    // slots fixed in advance (the i-th split node from the end takes the i-th
    // slot), which makes the arena the same at any thread count.
    std::vector<uint32_t> depth(nodes.size(), 0);
    uint32_t max_depth = 0;
    for (size_t i = 0; i < nodes.size(); ++i) {
        if (nodes[i].left < 0) continue;
        depth[size_t(nodes[i].left)] = depth[size_t(nodes[i].right)] = depth[i] + 1;
        max_depth = std::max(max_depth, depth[i] + 1);
    }
    std::vector<uint32_t> arena_of(nodes.size());
    std::vector<std::vector<uint32_t>> inner_by_depth(max_depth + 1);
    const size_t first_slot = arena.nodes.size();
    size_t slot = first_slot;
    for (size_t i = nodes.size(); i-- > 0;) {
        if (nodes[i].left < 0) {
            arena_of[i] = keys[nodes[i].begin].leaf;
        } else {
            arena_of[i] = uint32_t(slot++);
            inner_by_depth[depth[i]].push_back(uint32_t(i));
        }
    }
    arena.nodes.resize(slot);

    const size_t total_merges = leaves.size() - 1;
    size_t merges = 0;
    for (uint32_t d = max_depth + 1; d-- > 0;) {
        const std::vector<uint32_t>& level = inner_by_depth[d];
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, level.size(), 4096), [&](const tbb::blocked_range<size_t>& range) {
                for (size_t k = range.begin(); k != range.end(); ++k) {
                    const SplitNode& node = nodes[level[k]];
                    arena.nodes[arena_of[level[k]]] =
                        merge_clusters(arena, arena_of[size_t(node.left)], arena_of[size_t(node.right)],
                                       options.representative_rule, options.seed);
                }
            });
        merges += level.size();
        if (progress && !progress(double(merges) / double(total_merges))) {
            return make_error("cancelled during the lbvh build (" + std::to_string(merges) + " of " +
                                  std::to_string(total_merges) + " merges done)",
                              ErrorKind::kCancelled);
        }
    }
    return int32_t(arena_of[0]);
}

}  // namespace lc::bake

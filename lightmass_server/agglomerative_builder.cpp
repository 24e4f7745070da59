#include "lightmass_server/agglomerative_builder.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "lightmass_server/build_phase_timer.h"
#include "lightmass_server/cluster_attributes.h"
#include "lightmass_server/cluster_bvh.h"

namespace lc::bake {
namespace {

// Best-partner searches run in parallel chunks; progress (and cancel) is
// checked between chunks, from the calling thread only.
constexpr size_t kSearchChunk = 1u << 15;
// Merges only grow the BVH's bounds (removals leave them loose): recompute
// them after this fraction of the live clusters merged. Merged clusters sit
// where their children were, so the hierarchy itself stays good; it is rebuilt
// only to drop dead slots, once fewer than this fraction are live.
constexpr double kRefitFraction = 0.06;
constexpr double kRebuildLiveFraction = 0.5;
// A round's merges read their children's nodes this many pairs ahead, and the
// representatives' lights half as far ahead.
constexpr size_t kMergePrefetchAhead = 16;

ClusterShape shape_of(const BuildNode& node) {
    return ClusterShape{node.bbox_min, node.bbox_max, scalar_intensity(node)};
}

ClusterCone cone_of(const BuildNode& node) {
    return make_cluster_cone(node.cone_axis, node.cone_cos);
}

// The clusters of one build: local ids, their arena nodes, metric data.
struct ClusterState {
    ClusterSet set;
    std::vector<uint32_t> arena_of;
    std::vector<uint8_t> live;

    void add(const BuildNode& node, uint32_t arena_index) {
        set.shapes.push_back(shape_of(node));
        if (set.params.oriented()) set.cones.push_back(cone_of(node));
        arena_of.push_back(arena_index);
        live.push_back(1);
    }

    // Local clusters a and b become the local cluster of arena node
    // `arena_index` (already holding their merge).
    uint32_t adopt_merge(const BuildArena& arena, uint32_t a, uint32_t b, uint32_t arena_index) {
        live[a] = 0;
        live[b] = 0;
        add(arena.nodes[arena_index], arena_index);
        return uint32_t(arena_of.size() - 1);
    }

    // Merges local clusters a and b into a new arena node and local cluster.
    uint32_t merge(BuildArena& arena, uint32_t a, uint32_t b, const BuildOptions& options) {
        const BuildNode node = merge_clusters(arena, arena_of[a], arena_of[b],
                                              options.representative_rule, options.seed);
        arena.nodes.push_back(node);
        return adopt_merge(arena, a, b, uint32_t(arena.nodes.size() - 1));
    }
};

ClusterState initial_state(const BuildArena& arena, std::span<const uint32_t> leaves) {
    ClusterState state;
    state.set.params = agglomerative_metric_params(arena, leaves);
    const size_t capacity = 2 * leaves.size();
    state.set.shapes.reserve(capacity);
    if (state.set.params.oriented()) state.set.cones.reserve(capacity);
    state.arena_of.reserve(capacity);
    state.live.reserve(capacity);
    const size_t n = leaves.size();
    state.set.shapes.resize(n);
    if (state.set.params.oriented()) state.set.cones.resize(n);
    state.arena_of.assign(leaves.begin(), leaves.end());
    state.live.assign(n, 1);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1u << 12),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t i = range.begin(); i != range.end(); ++i) {
                              const BuildNode node = arena.node(leaves[i]);
                              state.set.shapes[i] = shape_of(node);
                              if (state.set.params.oriented()) state.set.cones[i] = cone_of(node);
                          }
                      });
    return state;
}

std::string cancelled_message(size_t merges, size_t total) {
    return "cancelled during agglomerative clustering (" + std::to_string(merges) + " of " +
           std::to_string(total) + " merges done)";
}

}  // namespace

MetricParams agglomerative_metric_params(const BuildArena& arena,
                                         std::span<const uint32_t> leaves) {
    MetricParams params;
    if (leaves.empty()) return params;
    glm::dvec3 lo(std::numeric_limits<double>::max());
    glm::dvec3 hi(std::numeric_limits<double>::lowest());
    double intensity_sum = 0.0;
    for (const uint32_t leaf : leaves) {
        const BuildNode node = arena.node(leaf);
        lo = glm::min(lo, node.bbox_min);
        hi = glm::max(hi, node.bbox_max);
        intensity_sum += scalar_intensity(node);
    }
    // c: the scene diagonal, for oriented lights only (the paper).
    const LightType type = arena.lights[leaves[0]].type;
    if (type == LightType::kSpot || type == LightType::kOriented) params.c2 = squared_diagonal(lo, hi);
    const double mean = intensity_sum / double(leaves.size());
    params.intensity_floor = mean > 0.0 ? 1e-15 * mean : 1.0;
    return params;
}

double total_cluster_metric(const BuildArena& arena, int32_t root, const MetricParams& params) {
    double total = 0.0;
    if (root < 0) return total;
    std::vector<int32_t> stack{root};
    while (!stack.empty()) {
        const BuildNode node = arena.node(uint32_t(stack.back()));
        stack.pop_back();
        if (node.is_leaf()) continue;
        const BuildNode l = arena.node(uint32_t(node.left));
        const BuildNode r = arena.node(uint32_t(node.right));
        if (!node.mixed_types) {
            total += cluster_metric(params, shape_of(l), shape_of(r), cone_of(l), cone_of(r));
        }
        stack.push_back(node.left);
        stack.push_back(node.right);
    }
    return total;
}

Result<int32_t> build_agglomerative_tree(BuildArena& arena, std::span<const uint32_t> leaves,
                                         const BuildOptions& options, const BuildProgressFn& progress,
                                         BuildReport& report) {
    if (leaves.empty()) return kNoBuildChild;
    if (leaves.size() == 1) return int32_t(leaves[0]);
    BuildPhaseTimer timer(report);

    const size_t n = leaves.size();
    const size_t total_merges = n - 1;
    const size_t capacity = 2 * n;
    ClusterState state = initial_state(arena, leaves);

    std::vector<uint32_t> live_ids(n);
    for (uint32_t i = 0; i < n; ++i) live_ids[i] = i;
    ClusterBvh bvh;
    bvh.build(state.set, live_ids, capacity);
    size_t merges_since_build = 0;

    // nearest[x]: x's best partner. Who points at whom, as linked lists in one
    // pool, so a merge finds the clusters that lost their partner.
    std::vector<NearestCluster> nearest(capacity);
    std::vector<uint32_t> pointed_by_head(capacity, kNoCluster);
    std::vector<std::pair<uint32_t, uint32_t>> pointed_by_pool;  // (cluster, next)
    pointed_by_pool.reserve(3 * n);

    std::vector<uint32_t> pending = live_ids;  // clusters needing a partner search
    std::vector<uint8_t> queued(capacity, 0);
    std::vector<uint32_t> hint(capacity, kNoCluster);  // a guess that starts each search
    std::vector<uint32_t> merged_into(capacity, kNoCluster);
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    std::vector<uint64_t> slot_keys;  // (BVH slot, cluster id), to sort the searches by slot
    timer.lap("agglomerative: clusters and their BVH");
    size_t merges = 0;
    size_t next_progress = 0;
    const size_t progress_step = std::max<size_t>(1, total_merges / 100);
    uint32_t last = 0;

    while (merges < total_merges) {
        // 1. Best partners, in parallel over independent searches, in BVH slot
        // order so that consecutive searches touch the same memory.
        slot_keys.resize(pending.size());
        const tbb::blocked_range<size_t> all_pending(0, pending.size(), 1u << 14);
        tbb::parallel_for(all_pending, [&](const tbb::blocked_range<size_t>& range) {
            for (size_t i = range.begin(); i != range.end(); ++i) {
                slot_keys[i] = (uint64_t(bvh.slot_of(pending[i])) << 32) | pending[i];
            }
        });
        tbb::parallel_sort(slot_keys.begin(), slot_keys.end());  // slots are unique: deterministic
        tbb::parallel_for(all_pending, [&](const tbb::blocked_range<size_t>& range) {
            for (size_t i = range.begin(); i != range.end(); ++i) pending[i] = uint32_t(slot_keys[i]);
        });
        timer.lap("agglomerative: round bookkeeping");
        for (size_t begin = 0; begin < pending.size(); begin += kSearchChunk) {
            const size_t end = std::min(pending.size(), begin + kSearchChunk);
            tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, 256),
                              [&](const tbb::blocked_range<size_t>& range) {
                                  std::vector<std::pair<double, uint32_t>> stack;
                                  for (size_t i = range.begin(); i != range.end(); ++i) {
                                      const uint32_t x = pending[i];
                                      nearest[x] = bvh.nearest(state.set, x, hint[x], stack);
                                  }
                              });
            if (progress && !progress(double(merges) / double(total_merges))) {
                return make_error(cancelled_message(merges, total_merges), ErrorKind::kCancelled);
            }
        }
        timer.lap("agglomerative: best-partner searches");
        for (const uint32_t x : pending) {
            const uint32_t y = nearest[x].id;
            if (y == kNoCluster) continue;
            pointed_by_pool.emplace_back(x, pointed_by_head[y]);
            pointed_by_head[y] = uint32_t(pointed_by_pool.size() - 1);
        }

        // 2. Mutual best partners merge. Only a cluster whose partner changed
        // can have become part of a new mutual pair.
        pairs.clear();
        for (const uint32_t x : pending) {
            const uint32_t y = nearest[x].id;
            if (y != kNoCluster && nearest[y].id == x) {
                pairs.emplace_back(std::min(x, y), std::max(x, y));
            }
        }
        if (pairs.empty()) {
            // Ties can close a cycle of best partners (x -> y -> z -> x, all
            // equal), and rounding can break the metric's monotonicity with
            // orientation cones: then merge the smallest recorded pair outright.
            uint32_t best = kNoCluster;
            for (const uint32_t x : pending) {
                if (best == kNoCluster || nearest[x].metric < nearest[best].metric) best = x;
            }
            if (best == kNoCluster || nearest[best].id == kNoCluster) {
                return make_error("agglomerative clustering found no pair to merge with " +
                                  std::to_string(total_merges - merges) + " merges left");
            }
            pairs.emplace_back(std::min(best, nearest[best].id), std::max(best, nearest[best].id));
        }
        tbb::parallel_sort(pairs.begin(), pairs.end());  // equal pairs are equal values: deterministic
        pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());

        // 3. Merge; the merged cluster takes the first child's BVH slot.
        std::vector<uint32_t> next_pending;
        next_pending.reserve(2 * pairs.size());
        // The cluster attributes of a round's merges are independent: compute
        // them in parallel into pre-sized arena slots, then adopt them in order.
        timer.lap("agglomerative: round bookkeeping");
        const size_t first_new = arena.nodes.size();
        arena.nodes.resize(first_new + pairs.size());
        tbb::parallel_for(tbb::blocked_range<size_t>(0, pairs.size(), 1024),
                          [&](const tbb::blocked_range<size_t>& range) {
                              for (size_t i = range.begin(); i != range.end(); ++i) {
                                  // The pairs' nodes lie at random in the arena.
                                  if (i + kMergePrefetchAhead < range.end()) {
                                      const auto [a, b] = pairs[i + kMergePrefetchAhead];
                                      prefetch_merge_input(arena, state.arena_of[a]);
                                      prefetch_merge_input(arena, state.arena_of[b]);
                                  }
                                  if (i + kMergePrefetchAhead / 2 < range.end()) {
                                      const auto [a, b] = pairs[i + kMergePrefetchAhead / 2];
                                      prefetch_representative_lights(arena, state.arena_of[a],
                                                                     state.arena_of[b]);
                                  }
                                  const auto [a, b] = pairs[i];
                                  arena.nodes[first_new + i] =
                                      merge_clusters(arena, state.arena_of[a], state.arena_of[b],
                                                     options.representative_rule, options.seed);
                              }
                          });
        timer.lap("agglomerative: cluster attributes");
        for (size_t i = 0; i < pairs.size(); ++i) {
            const auto [a, b] = pairs[i];
            last = state.adopt_merge(arena, a, b, uint32_t(first_new + i));
            bvh.merge(state.set, a, b, last);
            merged_into[a] = last;
            merged_into[b] = last;
            next_pending.push_back(last);
            queued[last] = 1;
            ++merges;
            ++merges_since_build;
            if (progress && merges >= next_progress) {
                next_progress = merges + progress_step;
                if (!progress(double(merges) / double(total_merges))) {
                    return make_error(cancelled_message(merges, total_merges), ErrorKind::kCancelled);
                }
            }
        }
        timer.lap("agglomerative: merges into the BVH");
        // 4. Clusters whose partner just merged away search again, starting
        // from the merged cluster; the merged cluster starts from the best of them.
        for (const auto& [a, b] : pairs) {
            const uint32_t merged = merged_into[a];
            double merged_hint_metric = std::numeric_limits<double>::infinity();
            hint[merged] = kNoCluster;
            for (const uint32_t gone : {a, b}) {
                for (uint32_t e = pointed_by_head[gone]; e != kNoCluster;
                     e = pointed_by_pool[e].second) {
                    const uint32_t x = pointed_by_pool[e].first;
                    if (!state.live[x] || nearest[x].id != gone) continue;
                    if (!queued[x]) {
                        queued[x] = 1;
                        next_pending.push_back(x);
                        hint[x] = merged;
                    }
                    const double m = cluster_metric(state.set, merged, x);
                    if (m < merged_hint_metric) {
                        merged_hint_metric = m;
                        hint[merged] = x;
                    }
                }
            }
        }
        for (const uint32_t x : next_pending) queued[x] = 0;
        pending.swap(next_pending);

        timer.lap("agglomerative: round bookkeeping");
        // 5. Fresh bounds once enough clusters changed.
        if (double(merges_since_build) >= kRefitFraction * double(bvh.live_count()) &&
            merges < total_merges) {
            if (double(bvh.live_count()) < kRebuildLiveFraction * double(bvh.slot_count())) {
                live_ids.clear();
                for (uint32_t x = 0; x < state.live.size(); ++x) {
                    if (state.live[x]) live_ids.push_back(x);
                }
                bvh.build(state.set, live_ids, capacity);
            } else {
                bvh.refit(state.set);
            }
            merges_since_build = 0;
        }
        timer.lap("agglomerative: BVH refits and rebuilds");
    }
    return int32_t(state.arena_of[last]);
}

Result<int32_t> build_agglomerative_tree_exact_greedy(BuildArena& arena,
                                                      std::span<const uint32_t> leaves,
                                                      const BuildOptions& options) {
    if (leaves.empty()) return kNoBuildChild;
    if (leaves.size() == 1) return int32_t(leaves[0]);
    ClusterState state = initial_state(arena, leaves);
    const size_t n = leaves.size();
    std::vector<NearestCluster> nearest(2 * n);

    // Exact best partner of x among live clusters, ties to the smaller id.
    const auto search = [&](uint32_t x) {
        NearestCluster best;
        for (uint32_t y = 0; y < state.live.size(); ++y) {
            if (!state.live[y] || y == x) continue;
            const double m = cluster_metric(state.set, x, y);
            if (m < best.metric || (m == best.metric && y < best.id)) best = {m, y};
        }
        return best;
    };
    for (uint32_t x = 0; x < n; ++x) nearest[x] = search(x);

    uint32_t last = 0;
    for (size_t merge = 0; merge + 1 < n; ++merge) {
        // The globally smallest pair: (metric, smaller id, larger id).
        uint32_t a = kNoCluster, b = kNoCluster;
        double best = std::numeric_limits<double>::infinity();
        for (uint32_t x = 0; x < state.live.size(); ++x) {
            if (!state.live[x]) continue;
            const uint32_t lo = std::min(x, nearest[x].id), hi = std::max(x, nearest[x].id);
            if (nearest[x].metric < best ||
                (nearest[x].metric == best && std::pair(lo, hi) < std::pair(a, b))) {
                best = nearest[x].metric;
                a = lo;
                b = hi;
            }
        }
        last = state.merge(arena, a, b, options);
        nearest.resize(std::max(nearest.size(), state.live.size()));
        nearest[last] = search(last);
        for (uint32_t x = 0; x < state.live.size(); ++x) {
            if (!state.live[x] || x == last) continue;
            if (nearest[x].id == a || nearest[x].id == b) {
                nearest[x] = search(x);
            } else {
                const double m = cluster_metric(state.set, x, last);
                if (m < nearest[x].metric) nearest[x] = {m, last};
            }
        }
    }
    return int32_t(state.arena_of[last]);
}

}  // namespace lc::bake

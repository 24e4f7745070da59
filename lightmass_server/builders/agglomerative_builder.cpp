#include "lightmass_server/builders/agglomerative_builder.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include "lightmass_server/builders/build_phase_timer.h"
#include "lightmass_server/builders/cluster_attributes.h"
#include "lightmass_server/builders/cluster_bvh.h"
#include "lightcuts/status_macros.h"

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
        if (!node.flags.mixed_types()) {
            total += cluster_metric(params, shape_of(l), shape_of(r), cone_of(l), cone_of(r));
        }
        stack.push_back(node.left);
        stack.push_back(node.right);
    }
    return total;
}

namespace {

// One build's rounds (the paper's agglomerative clustering, in rounds of
// mutual best partners): each round searches the pending clusters' best
// partners, merges the mutual pairs, queues the clusters that lost their
// partner, and refreshes the BVH's bounds now and then.
class AgglomerativeRounds {
public:
    AgglomerativeRounds(BuildArena& arena, std::span<const uint32_t> leaves, const BuildOptions& options,
                        const BuildProgressFn& progress, BuildPhaseTimer& timer)
        : arena_(arena), options_(options), progress_(progress), timer_(timer),
          total_merges_(leaves.size() - 1), capacity_(2 * leaves.size()),
          progress_step_(std::max<size_t>(1, total_merges_ / 100)),
          state_(initial_state(arena, leaves)), nearest_(capacity_),
          pointed_by_head_(capacity_, kNoCluster), queued_(capacity_, 0), hint_(capacity_, kNoCluster),
          merged_into_(capacity_, kNoCluster) {
        live_ids_.resize(leaves.size());
        for (uint32_t i = 0; i < leaves.size(); ++i) live_ids_[i] = i;
        bvh_.build(state_.set, live_ids_, capacity_);
        pointed_by_pool_.reserve(3 * leaves.size());
        pending_ = live_ids_;
        timer_.lap("agglomerative: clusters and their BVH");
    }

    // The root's arena index.
    Result<int32_t> run() {
        while (merges_ < total_merges_) {
            sort_pending_by_slot();
            LC_RETURN_IF_ERROR(search_best_partners());
            record_who_points_at_whom();
            LC_RETURN_IF_ERROR(find_mutual_pairs());
            std::vector<uint32_t> next_pending;
            next_pending.reserve(2 * pairs_.size());
            LC_RETURN_IF_ERROR(merge_pairs(next_pending));
            queue_the_orphaned(next_pending);
            for (const uint32_t x : next_pending) queued_[x] = 0;
            pending_.swap(next_pending);
            timer_.lap("agglomerative: round bookkeeping");
            refresh_bvh_bounds();
            timer_.lap("agglomerative: BVH refits and rebuilds");
        }
        return int32_t(state_.arena_of[last_]);
    }

private:
    // In BVH slot order, so that consecutive searches touch the same memory.
    void sort_pending_by_slot() {
        slot_keys_.resize(pending_.size());
        const tbb::blocked_range<size_t> all_pending(0, pending_.size(), 1u << 14);
        tbb::parallel_for(all_pending, [&](const tbb::blocked_range<size_t>& range) {
            for (size_t i = range.begin(); i != range.end(); ++i) {
                slot_keys_[i] = (uint64_t(bvh_.slot_of(pending_[i])) << 32) | pending_[i];
            }
        });
        tbb::parallel_sort(slot_keys_.begin(), slot_keys_.end());  // slots are unique: deterministic
        tbb::parallel_for(all_pending, [&](const tbb::blocked_range<size_t>& range) {
            for (size_t i = range.begin(); i != range.end(); ++i) pending_[i] = uint32_t(slot_keys_[i]);
        });
        timer_.lap("agglomerative: round bookkeeping");
    }

    // In parallel over independent searches, in chunks with progress between them.
    Status search_best_partners() {
        for (size_t begin = 0; begin < pending_.size(); begin += kSearchChunk) {
            const size_t end = std::min(pending_.size(), begin + kSearchChunk);
            tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, 256),
                              [&](const tbb::blocked_range<size_t>& range) {
                                  std::vector<std::pair<double, uint32_t>> stack;
                                  for (size_t i = range.begin(); i != range.end(); ++i) {
                                      const uint32_t x = pending_[i];
                                      nearest_[x] = bvh_.nearest(state_.set, x, hint_[x], stack);
                                  }
                              });
            if (progress_ && !progress_(double(merges_) / double(total_merges_))) return cancelled();
        }
        timer_.lap("agglomerative: best-partner searches");
        return Ok{};
    }

    // nearest_[x]: x's best partner. Who points at whom, as linked lists in one
    // pool, so a merge finds the clusters that lost their partner.
    void record_who_points_at_whom() {
        for (const uint32_t x : pending_) {
            const uint32_t y = nearest_[x].id;
            if (y == kNoCluster) continue;
            pointed_by_pool_.emplace_back(x, pointed_by_head_[y]);
            pointed_by_head_[y] = uint32_t(pointed_by_pool_.size() - 1);
        }
    }

    // Only a cluster whose partner changed can have become part of a new mutual pair.
    Status find_mutual_pairs() {
        pairs_.clear();
        for (const uint32_t x : pending_) {
            const uint32_t y = nearest_[x].id;
            if (y != kNoCluster && nearest_[y].id == x) pairs_.emplace_back(std::min(x, y), std::max(x, y));
        }
        if (pairs_.empty()) LC_RETURN_IF_ERROR(add_smallest_recorded_pair());
        tbb::parallel_sort(pairs_.begin(), pairs_.end());  // equal pairs are equal values: deterministic
        pairs_.erase(std::unique(pairs_.begin(), pairs_.end()), pairs_.end());
        return Ok{};
    }

    // Ties can close a cycle of best partners (x -> y -> z -> x, all equal), and
    // rounding can break the metric's monotonicity with orientation cones: then
    // the smallest recorded pair merges outright.
    Status add_smallest_recorded_pair() {
        uint32_t best = kNoCluster;
        for (const uint32_t x : pending_) {
            if (best == kNoCluster || nearest_[x].metric < nearest_[best].metric) best = x;
        }
        if (best == kNoCluster || nearest_[best].id == kNoCluster) {
            return make_error("agglomerative clustering found no pair to merge with " +
                              std::to_string(total_merges_ - merges_) + " merges left");
        }
        pairs_.emplace_back(std::min(best, nearest_[best].id), std::max(best, nearest_[best].id));
        return Ok{};
    }

    // The merged cluster takes the first child's BVH slot.
    Status merge_pairs(std::vector<uint32_t>& next_pending) {
        timer_.lap("agglomerative: round bookkeeping");
        const size_t first_new = compute_merged_nodes();
        timer_.lap("agglomerative: cluster attributes");
        for (size_t i = 0; i < pairs_.size(); ++i) {
            const auto [a, b] = pairs_[i];
            last_ = state_.adopt_merge(arena_, a, b, uint32_t(first_new + i));
            bvh_.merge(state_.set, a, b, last_);
            merged_into_[a] = last_;
            merged_into_[b] = last_;
            next_pending.push_back(last_);
            queued_[last_] = 1;
            ++merges_;
            ++merges_since_build_;
            if (progress_ && merges_ >= next_progress_) {
                next_progress_ = merges_ + progress_step_;
                if (!progress_(double(merges_) / double(total_merges_))) return cancelled();
            }
        }
        timer_.lap("agglomerative: merges into the BVH");
        return Ok{};
    }

    // A round's merges are independent: their cluster attributes are computed in
    // parallel into pre-sized arena slots (adopted in order afterwards). Returns the first slot.
    size_t compute_merged_nodes() {
        const size_t first_new = arena_.nodes.size();
        arena_.nodes.resize(first_new + pairs_.size());
        tbb::parallel_for(tbb::blocked_range<size_t>(0, pairs_.size(), 1024),
                          [&](const tbb::blocked_range<size_t>& range) {
                              for (size_t i = range.begin(); i != range.end(); ++i) {
                                  prefetch_ahead_of(i, range.end());
                                  const auto [a, b] = pairs_[i];
                                  arena_.nodes[first_new + i] =
                                      merge_clusters(arena_, state_.arena_of[a], state_.arena_of[b],
                                                     options_.representative_rule, options_.seed);
                              }
                          });
        return first_new;
    }

    // The pairs' nodes lie at random in the arena.
    void prefetch_ahead_of(size_t i, size_t end) const {
        if (i + kMergePrefetchAhead < end) {
            const auto [a, b] = pairs_[i + kMergePrefetchAhead];
            prefetch_merge_input(arena_, state_.arena_of[a]);
            prefetch_merge_input(arena_, state_.arena_of[b]);
        }
        if (i + kMergePrefetchAhead / 2 < end) {
            const auto [a, b] = pairs_[i + kMergePrefetchAhead / 2];
            prefetch_representative_lights(arena_, state_.arena_of[a], state_.arena_of[b]);
        }
    }

    // Clusters whose partner just merged away search again, starting from the
    // merged cluster; the merged cluster starts from the best of them.
    void queue_the_orphaned(std::vector<uint32_t>& next_pending) {
        for (const auto& [a, b] : pairs_) {
            const uint32_t merged = merged_into_[a];
            double merged_hint_metric = std::numeric_limits<double>::infinity();
            hint_[merged] = kNoCluster;
            for (const uint32_t gone : {a, b}) {
                for (uint32_t e = pointed_by_head_[gone]; e != kNoCluster; e = pointed_by_pool_[e].second) {
                    const uint32_t x = pointed_by_pool_[e].first;
                    if (!state_.live[x] || nearest_[x].id != gone) continue;
                    if (!queued_[x]) {
                        queued_[x] = 1;
                        next_pending.push_back(x);
                        hint_[x] = merged;
                    }
                    const double m = cluster_metric(state_.set, merged, x);
                    if (m < merged_hint_metric) {
                        merged_hint_metric = m;
                        hint_[merged] = x;
                    }
                }
            }
        }
    }

    // Fresh bounds once enough clusters changed.
    void refresh_bvh_bounds() {
        if (double(merges_since_build_) < kRefitFraction * double(bvh_.live_count()) ||
            merges_ >= total_merges_) {
            return;
        }
        if (double(bvh_.live_count()) < kRebuildLiveFraction * double(bvh_.slot_count())) {
            live_ids_.clear();
            for (uint32_t x = 0; x < state_.live.size(); ++x) {
                if (state_.live[x]) live_ids_.push_back(x);
            }
            bvh_.build(state_.set, live_ids_, capacity_);
        } else {
            bvh_.refit(state_.set);
        }
        merges_since_build_ = 0;
    }

    Error cancelled() const {
        return make_error(cancelled_message(merges_, total_merges_), ErrorKind::kCancelled);
    }

    BuildArena& arena_;
    const BuildOptions& options_;
    const BuildProgressFn& progress_;
    BuildPhaseTimer& timer_;
    const size_t total_merges_;
    const size_t capacity_;
    const size_t progress_step_;
    ClusterState state_;
    ClusterBvh bvh_;
    std::vector<uint32_t> live_ids_;
    size_t merges_since_build_ = 0;
    std::vector<NearestCluster> nearest_;
    std::vector<uint32_t> pointed_by_head_;
    std::vector<std::pair<uint32_t, uint32_t>> pointed_by_pool_;  // (cluster, next)
    std::vector<uint32_t> pending_;  // clusters needing a partner search
    std::vector<uint8_t> queued_;
    std::vector<uint32_t> hint_;  // a guess that starts each search
    std::vector<uint32_t> merged_into_;
    std::vector<std::pair<uint32_t, uint32_t>> pairs_;
    std::vector<uint64_t> slot_keys_;  // (BVH slot, cluster id), to sort the searches by slot
    size_t merges_ = 0;
    size_t next_progress_ = 0;
    uint32_t last_ = 0;
};

}  // namespace

Result<int32_t> build_agglomerative_tree(BuildArena& arena, std::span<const uint32_t> leaves,
                                         const BuildOptions& options, const BuildProgressFn& progress,
                                         BuildReport& report) {
    if (leaves.empty()) return kNoChild;
    if (leaves.size() == 1) return int32_t(leaves[0]);
    BuildPhaseTimer timer(report);
    return AgglomerativeRounds(arena, leaves, options, progress, timer).run();
}

Result<int32_t> build_agglomerative_tree_exact_greedy(BuildArena& arena,
                                                      std::span<const uint32_t> leaves,
                                                      const BuildOptions& options) {
    if (leaves.empty()) return kNoChild;
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

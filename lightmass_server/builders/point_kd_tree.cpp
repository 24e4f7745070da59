#include "lightmass_server/builders/point_kd_tree.h"

#include "lightmass_server/builders/stoppable_select.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace lc::bake {
namespace {

constexpr uint32_t kLeafSize = 8;

struct KdNode {
    glm::dvec3 box_min{0.0};
    glm::dvec3 box_max{0.0};
    uint32_t begin = 0;  // range of `order`
    uint32_t end = 0;
    int32_t left = -1;  // children; -1 for a leaf
    int32_t right = -1;
};

struct KdTree {
    std::vector<uint32_t> order;
    std::vector<KdNode> nodes;
};

// A stop leaves the tree partial (unsplit nodes, no boxes): the caller asks it and drops the tree.
KdTree build_kd_tree(std::span<const glm::dvec3> points, const BakeStop* stop = nullptr) {
    KdTree tree;
    tree.order.resize(points.size());
    for (uint32_t i = 0; i < points.size(); ++i) tree.order[i] = i;
    tree.nodes.reserve(2 * points.size() / kLeafSize + 2);
    tree.nodes.push_back(KdNode{{}, {}, 0, uint32_t(points.size())});

    // Explicit work list instead of recursion: depth is log n anyway, but the
    // builder never relies on it.
    std::vector<uint32_t> pending{0};
    StopPoll poll(stop);
    while (!pending.empty() && !poll.now()) {
        const uint32_t node_index = pending.back();
        pending.pop_back();
        const uint32_t begin = tree.nodes[node_index].begin;
        const uint32_t end = tree.nodes[node_index].end;

        glm::dvec3 lo(std::numeric_limits<double>::max());
        glm::dvec3 hi(std::numeric_limits<double>::lowest());
        for (uint32_t i = begin; i < end; ++i) {
            if ((i & 0xFFFFu) == 0 && poll.now()) return tree;  // the root's box reads 4 M points
            lo = glm::min(lo, points[tree.order[i]]);
            hi = glm::max(hi, points[tree.order[i]]);
        }
        tree.nodes[node_index].box_min = lo;
        tree.nodes[node_index].box_max = hi;
        if (end - begin <= kLeafSize) continue;

        const glm::dvec3 extent = hi - lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0
                         : extent.y >= extent.z                       ? 1
                                                                      : 2;
        const uint32_t mid = begin + (end - begin) / 2;
        // A strict total order (coordinate, then index) makes the split unique,
        // so the nodes hold the same points however the selection arranges them.
        const auto below = [&](uint32_t a, uint32_t b) {
            const double ca = points[a][axis];
            const double cb = points[b][axis];
            return ca < cb || (ca == cb && a < b);
        };
        if (!stoppable_nth_element(tree.order.data(), begin, mid, end, below, poll)) return tree;
        const int32_t left = int32_t(tree.nodes.size());
        tree.nodes.push_back(KdNode{{}, {}, begin, mid});
        tree.nodes.push_back(KdNode{{}, {}, mid, end});
        tree.nodes[node_index].left = left;
        tree.nodes[node_index].right = left + 1;
        pending.push_back(uint32_t(left));
        pending.push_back(uint32_t(left + 1));
    }
    return tree;
}

double box_distance2(const KdNode& node, const glm::dvec3& q) {
    const glm::dvec3 d = glm::max(glm::dvec3(0.0), glm::max(node.box_min - q, q - node.box_max));
    return d.x * d.x + d.y * d.y + d.z * d.z;
}

struct Candidate {
    double distance2;
    uint32_t index;
    bool operator<(const Candidate& o) const {
        return distance2 < o.distance2 || (distance2 == o.distance2 && index < o.index);
    }
};

// The k nearest other points of point `query` under the (distance, index)
// order, nearest first, left in `best`.
void query_neighbors(const KdTree& tree, std::span<const glm::dvec3> points, uint32_t query,
                     uint32_t k, std::vector<Candidate>& best,
                     std::vector<std::pair<double, uint32_t>>& stack) {
    const glm::dvec3 q = points[query];
    best.clear();  // a max-heap on Candidate order
    stack.clear();
    stack.emplace_back(0.0, 0u);
    while (!stack.empty()) {
        const auto [bound2, node_index] = stack.back();
        stack.pop_back();
        if (best.size() == k && bound2 > best.front().distance2) continue;
        const KdNode& node = tree.nodes[node_index];
        if (node.left < 0) {
            for (uint32_t i = node.begin; i < node.end; ++i) {
                const uint32_t p = tree.order[i];
                if (p == query) continue;
                const Candidate c{squared_distance(points[p], q), p};
                if (best.size() < k) {
                    best.push_back(c);
                    std::push_heap(best.begin(), best.end());
                } else if (c < best.front()) {
                    std::pop_heap(best.begin(), best.end());
                    best.back() = c;
                    std::push_heap(best.begin(), best.end());
                }
            }
            continue;
        }
        // Visit the nearer child first: push it last.
        const double dl = box_distance2(tree.nodes[size_t(node.left)], q);
        const double dr = box_distance2(tree.nodes[size_t(node.right)], q);
        if (dl <= dr) {
            stack.emplace_back(dr, uint32_t(node.right));
            stack.emplace_back(dl, uint32_t(node.left));
        } else {
            stack.emplace_back(dl, uint32_t(node.left));
            stack.emplace_back(dr, uint32_t(node.right));
        }
    }
    std::sort_heap(best.begin(), best.end());
}

// Queries every point's k nearest, handing each list to write(point, best).
template <class Write>
void for_each_neighbor_list(std::span<const glm::dvec3> points, uint32_t k, const BakeStop* stop,
                            const Write& write) {
    const KdTree tree = build_kd_tree(points, stop);
    if (stop_requested(stop)) return;
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, uint32_t(points.size()), 256),
                      [&](const tbb::blocked_range<uint32_t>& range) {
                          // Per point, not per chunk: TBB's chunks can hold n / (a few x threads) points.
                          StopPoll poll(stop);
                          std::vector<Candidate> best;
                          std::vector<std::pair<double, uint32_t>> stack;
                          for (uint32_t i = range.begin(); i != range.end(); ++i) {
                              if (poll()) return;  // the result is dropped
                              query_neighbors(tree, points, i, k, best, stack);
                              write(i, best);
                          }
                      });
}

// Smallest offset in each node's subtree; children come after their parent.
std::vector<double> subtree_min_offsets(const KdTree& tree, std::span<const double> offset) {
    std::vector<double> min_offset(tree.nodes.size(), std::numeric_limits<double>::infinity());
    for (size_t i = tree.nodes.size(); i-- > 0;) {
        const KdNode& node = tree.nodes[i];
        if (node.left < 0) {
            for (uint32_t k = node.begin; k < node.end; ++k) {
                min_offset[i] = std::min(min_offset[i], offset[tree.order[k]]);
            }
        } else {
            min_offset[i] = std::min(min_offset[size_t(node.left)], min_offset[size_t(node.right)]);
        }
    }
    return min_offset;
}

}  // namespace

std::vector<std::pair<uint32_t, uint32_t>> pairs_below_negative_offsets(
    std::span<const glm::dvec3> points, std::span<const double> offset, double tolerance,
    const BakeStop* stop) {
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    if (points.size() < 2) return pairs;
    const KdTree tree = build_kd_tree(points, stop);
    if (stop_requested(stop)) return pairs;
    const std::vector<double> min_offset = subtree_min_offsets(tree, offset);
    const uint32_t n = uint32_t(points.size());
    std::vector<std::vector<uint32_t>> partners(n);
    tbb::parallel_for(
        tbb::blocked_range<uint32_t>(0, n, 64), [&](const tbb::blocked_range<uint32_t>& range) {
            // Per point, not per chunk: TBB's chunks can hold n / (a few x threads) points.
            StopPoll poll(stop);
            std::vector<uint32_t> stack;
            for (uint32_t u = range.begin(); u != range.end(); ++u) {
                if (poll()) return;  // the pairs are dropped
                const glm::dvec3 p = points[u];
                const double limit = -tolerance - offset[u];
                stack.assign(1, 0u);
                while (!stack.empty()) {
                    const uint32_t i = stack.back();
                    stack.pop_back();
                    const KdNode& node = tree.nodes[i];
                    // The box distance may round above the true
                    // distance of a point in it: shave it.
                    const double nearest = std::sqrt(box_distance2(node, p)) * (1.0 - 1e-12);
                    if (nearest + min_offset[i] >= limit) continue;
                    if (node.left >= 0) {
                        stack.push_back(uint32_t(node.left));
                        stack.push_back(uint32_t(node.right));
                        continue;
                    }
                    for (uint32_t k = node.begin; k < node.end; ++k) {
                        const uint32_t v = tree.order[k];
                        if (v > u && glm::distance(p, points[v]) + offset[v] < limit) {
                            partners[u].push_back(v);
                        }
                    }
                }
                std::sort(partners[u].begin(), partners[u].end());
            }
        });
    for (uint32_t u = 0; u < n; ++u) {
        for (const uint32_t v : partners[u]) pairs.emplace_back(u, v);
    }
    return pairs;
}

KnnResult k_nearest_neighbors(std::span<const glm::dvec3> points, uint32_t k, const BakeStop* stop) {
    KnnResult result;
    if (points.size() < 2) return result;
    const uint32_t k_used = result.k_used = std::min<uint32_t>(k, uint32_t(points.size() - 1));
    result.neighbors.resize(points.size() * k_used);
    for_each_neighbor_list(points, k_used, stop, [&](uint32_t i, const std::vector<Candidate>& best) {
        Neighbor* out = &result.neighbors[size_t(i) * k_used];
        for (uint32_t j = 0; j < best.size(); ++j) out[j] = Neighbor{best[j].index, std::sqrt(best[j].distance2)};
    });
    return result;
}

KnnIndices k_nearest_indices(std::span<const glm::dvec3> points, uint32_t k, const BakeStop* stop) {
    KnnIndices result;
    if (points.size() < 2) return result;
    const uint32_t k_used = result.k_used = std::min<uint32_t>(k, uint32_t(points.size() - 1));
    result.indices.resize(points.size() * k_used);
    for_each_neighbor_list(points, k_used, stop, [&](uint32_t i, const std::vector<Candidate>& best) {
        uint32_t* out = &result.indices[size_t(i) * k_used];
        for (uint32_t j = 0; j < best.size(); ++j) out[j] = best[j].index;
    });
    return result;
}

}  // namespace lc::bake

#include "lightmass_server/builders/approximate_pairing.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <tuple>

#include "lightmass_server/builders/point_kd_tree.h"
#include "lightmass_server/builders/stoppable_sort.h"

namespace lc::bake {
namespace {

constexpr uint32_t kCandidateNeighbors = 8;
constexpr uint32_t kRetryNeighbors = 4;
constexpr int kMaxTwoOptPasses = 16;
constexpr uint32_t kUnmatched = kNoCarriedNode;

struct CandidateEdge {
    double distance;
    uint32_t u;
    uint32_t v;
    bool operator<(const CandidateEdge& o) const {
        return std::tie(distance, u, v) < std::tie(o.distance, o.u, o.v);
    }
};

// |p_a - p_b| as the k-NN measured it: the same bits whichever end comes first
// (the difference's components only change sign).
double length(std::span<const glm::dvec3> points, uint32_t a, uint32_t b) {
    return std::sqrt(squared_distance(points[b], points[a]));
}

// An edge once sorted: its length is recomputed when needed, so the level keeps
// 8 bytes an edge through the matching instead of 16 (less for a stop to free).
struct EdgeEnds {
    uint32_t u;
    uint32_t v;
};

// Point i's list gives the edge {i, j} unless j < i lists i too (then j's
// list gave it): every undirected edge once, so no de-duplicating pass over
// 40 M edges, and a third fewer of them to sort, keep and free.
bool listed_by_smaller(const KnnIndices& knn, uint32_t i, uint32_t j) {
    if (j > i) return false;
    const std::span<const uint32_t> of_j = knn.of(j);
    return std::find(of_j.begin(), of_j.end(), i) != of_j.end();
}

// Undirected candidate edges (u < v after mapping through `ids`) from k-NN
// lists, unsorted. A distance is recomputed from the points the way the k-NN
// ranked them, so it is the one the k-NN saw, bit for bit.
std::vector<CandidateEdge> unsorted_candidate_edges(std::span<const glm::dvec3> points, const KnnIndices& knn,
                                                    std::span<const uint32_t> ids, StopPoll& poll) {
    std::vector<CandidateEdge> edges;
    edges.reserve(ids.size() * knn.k_used);  // pages only the edges made touch
    for (uint32_t i = 0; i < ids.size(); ++i) {
        if (poll()) return {};
        for (const uint32_t j : knn.of(i)) {
            if (listed_by_smaller(knn, i, j)) continue;
            edges.push_back(CandidateEdge{length(points, i, j), std::min(ids[i], ids[j]), std::max(ids[i], ids[j])});
        }
    }
    return edges;
}

// Sorted by (distance, u, v); stopped, empty. The edges are distinct under a
// total order, so the result does not depend on how it sorts.
std::vector<CandidateEdge> sorted(std::vector<CandidateEdge> edges, StopPoll& poll) {
    if (!stoppable_sort(std::span<CandidateEdge>(edges), std::less<CandidateEdge>(), poll)) return {};
    return edges;
}

template <class Edge>
void greedy_match(std::span<const Edge> edges, std::vector<uint32_t>& mate, StopPoll& poll) {
    for (const Edge& e : edges) {
        if (poll()) return;
        if (mate[e.u] == kUnmatched && mate[e.v] == kUnmatched) {
            mate[e.u] = e.v;
            mate[e.v] = e.u;
        }
    }
}

// Exchanges (u, mu), (v, mv) for (u, v), (mu, mv) while that is cheaper. The
// dummy node n (mate of the carried node) costs nothing to pair with.
void two_opt(std::span<const glm::dvec3> points, std::span<const EdgeEnds> edges,
             std::vector<uint32_t>& mate, StopPoll& poll) {
    const uint32_t dummy = uint32_t(points.size());
    const auto cost = [&](uint32_t a, uint32_t b) {
        return a == dummy || b == dummy ? 0.0 : glm::distance(points[a], points[b]);
    };
    for (int pass = 0; pass < kMaxTwoOptPasses; ++pass) {
        bool improved = false;
        for (const EdgeEnds& e : edges) {
            if (poll()) return;
            const uint32_t u = e.u;
            const uint32_t v = e.v;
            const uint32_t mu = mate[u];
            const uint32_t mv = mate[v];
            if (mu == v) continue;
            const double current = cost(u, mu) + cost(v, mv);
            const double exchanged = length(points, u, v) + cost(mu, mv);
            // The relative margin keeps rounding from cycling between equal pairings.
            if (exchanged < current * (1.0 - 1e-12)) {
                mate[u] = v;
                mate[v] = u;
                mate[mu] = mv;
                mate[mv] = mu;
                improved = true;
            }
        }
        if (!improved) break;
    }
}

double lower_bound_from(std::span<const glm::dvec3> points, const KnnIndices& knn) {
    const uint32_t n = uint32_t(points.size());
    double sum = 0.0;
    double largest = 0.0;
    for (uint32_t u = 0; u < n; ++u) {
        const double nn = std::sqrt(squared_distance(points[knn.of(u)[0]], points[u]));
        sum += nn;
        largest = std::max(largest, nn);
    }
    // An odd level carries one node that pays nothing: drop the largest term.
    if (n % 2 == 1) sum -= largest;
    return std::max(0.0, 0.5 * sum);
}

struct CandidateGraph {
    std::vector<CandidateEdge> unsorted;  // as made, before the sort
    std::vector<EdgeEnds> edges;          // sorted by (length, u, v)
    double lower_bound = 0.0;
};

// The level's candidate edges, unsorted, and its lower bound: the k-NN lists
// are freed on return, before the sort and the matching, so a stop in the
// level's later steps has less to give back.
CandidateGraph unsorted_candidate_graph(std::span<const glm::dvec3> points, const BakeStop* stop,
                                        StopPoll& poll) {
    const KnnIndices knn = k_nearest_indices(points, kCandidateNeighbors, stop);
    if (poll.now()) return {};
    std::vector<uint32_t> all_ids(points.size());
    for (uint32_t i = 0; i < points.size(); ++i) all_ids[i] = i;
    CandidateGraph graph;
    graph.unsorted = unsorted_candidate_edges(points, knn, all_ids, poll);
    if (poll()) return {};
    graph.lower_bound = lower_bound_from(points, knn);
    return graph;
}

// The sorted edges' ends: 8 bytes an edge through the matching instead of 16.
CandidateGraph candidate_graph(std::span<const glm::dvec3> points, const BakeStop* stop, StopPoll& poll) {
    CandidateGraph graph = unsorted_candidate_graph(points, stop, poll);
    const std::vector<CandidateEdge> edges = sorted(std::move(graph.unsorted), poll);
    graph.edges.reserve(edges.size());
    for (const CandidateEdge& e : edges) {
        if (poll()) return {};
        graph.edges.push_back(EdgeEnds{e.u, e.v});
    }
    return graph;
}

}  // namespace

double nearest_neighbor_lower_bound(std::span<const glm::dvec3> points) {
    if (points.size() < 2) return 0.0;
    return lower_bound_from(points, k_nearest_indices(points, 1));
}

LevelPairing approximate_pairing(std::span<const glm::dvec3> points, const BakeStop* stop) {
    const uint32_t n = uint32_t(points.size());
    if (n < 2) {
        LevelPairing trivial;
        trivial.carried = n == 1 ? 0 : kNoCarriedNode;
        trivial.exact = true;
        return trivial;
    }

    // A stop leaves the pairing partial: the builder asks the stop and drops it.
    StopPoll poll(stop);
    const CandidateGraph graph = candidate_graph(points, stop, poll);
    if (poll()) return {};
    const std::span<const EdgeEnds> edges = graph.edges;

    // mate has one extra slot: the dummy node n, partner of the carried node.
    std::vector<uint32_t> mate(size_t(n) + 1, kUnmatched);
    greedy_match(edges, mate, poll);

    // Points whose candidates were all taken: pair them among themselves. Every
    // round matches at least the closest remaining pair, so this terminates.
    std::vector<uint32_t> free_ids;
    std::vector<glm::dvec3> free_points;
    while (!poll.now()) {
        free_ids.clear();
        free_points.clear();
        for (uint32_t u = 0; u < n; ++u) {
            if (mate[u] == kUnmatched) {
                free_ids.push_back(u);
                free_points.push_back(points[u]);
            }
        }
        if (free_ids.size() < 2) break;
        const KnnIndices free_knn = k_nearest_indices(free_points, kRetryNeighbors, stop);
        greedy_match(std::span<const CandidateEdge>(
                         sorted(unsorted_candidate_edges(free_points, free_knn, free_ids, poll), poll)),
                     mate, poll);
    }
    if (free_ids.size() == 1) {
        mate[free_ids[0]] = n;
        mate[n] = free_ids[0];
    }

    if (poll()) return {};
    two_opt(points, edges, mate, poll);
    if (poll()) return {};

    LevelPairing pairing = pairing_from_mates(points, std::span<const uint32_t>(mate).first(n));
    pairing.lower_bound = std::min(pairing.cost, graph.lower_bound);
    pairing.exact = false;
    return pairing;
}

}  // namespace lc::bake

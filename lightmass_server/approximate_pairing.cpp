#include "lightmass_server/approximate_pairing.h"

#include <algorithm>
#include <tuple>

#include "lightmass_server/point_kd_tree.h"

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
    bool operator==(const CandidateEdge& o) const { return u == o.u && v == o.v; }
};

// std::sort in runs merged pairwise, asking the poll between runs and merges:
// the same order (the comparison is a total order on distinct edges), and a
// stop seen within one run's work instead of after sorting 32 million edges.
void sort_edges(std::vector<CandidateEdge>& edges, StopPoll& poll) {
    constexpr size_t kRun = size_t(1) << 18;
    const auto at = [&](size_t i) { return edges.begin() + std::ptrdiff_t(std::min(i, edges.size())); };
    for (size_t begin = 0; begin < edges.size(); begin += kRun) {
        if (poll.now()) return;
        std::sort(at(begin), at(begin + kRun));
    }
    for (size_t width = kRun; width < edges.size(); width *= 2) {
        for (size_t begin = 0; begin + width < edges.size(); begin += 2 * width) {
            if (poll.now()) return;
            std::inplace_merge(at(begin), at(begin + width), at(begin + 2 * width));
        }
    }
}

// Undirected candidate edges (u < v) from k-NN lists, mapped through `ids`,
// sorted by (distance, u, v) and without duplicates.
std::vector<CandidateEdge> candidate_edges(const KnnResult& knn, std::span<const uint32_t> ids,
                                           StopPoll& poll) {
    std::vector<CandidateEdge> edges;
    edges.reserve(ids.size() * knn.k_used);
    for (uint32_t i = 0; i < ids.size(); ++i) {
        if (poll()) return {};
        for (const Neighbor& nb : knn.of(i)) {
            const uint32_t a = ids[i];
            const uint32_t b = ids[nb.index];
            edges.push_back(CandidateEdge{nb.distance, std::min(a, b), std::max(a, b)});
        }
    }
    sort_edges(edges, poll);
    if (poll.now()) return {};  // not a pass over 40 M edges (4 M lights) left half sorted
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    return edges;
}

void greedy_match(std::span<const CandidateEdge> edges, std::vector<uint32_t>& mate, StopPoll& poll) {
    for (const CandidateEdge& e : edges) {
        if (poll()) return;
        if (mate[e.u] == kUnmatched && mate[e.v] == kUnmatched) {
            mate[e.u] = e.v;
            mate[e.v] = e.u;
        }
    }
}

// Exchanges (u, mu), (v, mv) for (u, v), (mu, mv) while that is cheaper. The
// dummy node n (mate of the carried node) costs nothing to pair with.
void two_opt(std::span<const glm::dvec3> points, std::span<const CandidateEdge> edges,
             std::vector<uint32_t>& mate, StopPoll& poll) {
    const uint32_t dummy = uint32_t(points.size());
    const auto cost = [&](uint32_t a, uint32_t b) {
        return a == dummy || b == dummy ? 0.0 : glm::distance(points[a], points[b]);
    };
    for (int pass = 0; pass < kMaxTwoOptPasses; ++pass) {
        bool improved = false;
        for (const CandidateEdge& e : edges) {
            if (poll()) return;
            const uint32_t u = e.u;
            const uint32_t v = e.v;
            const uint32_t mu = mate[u];
            const uint32_t mv = mate[v];
            if (mu == v) continue;
            const double current = cost(u, mu) + cost(v, mv);
            const double exchanged = e.distance + cost(mu, mv);
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

double lower_bound_from(const KnnResult& knn, uint32_t n) {
    double sum = 0.0;
    double largest = 0.0;
    for (uint32_t u = 0; u < n; ++u) {
        const double nn = knn.of(u)[0].distance;
        sum += nn;
        largest = std::max(largest, nn);
    }
    // An odd level carries one node that pays nothing: drop the largest term.
    if (n % 2 == 1) sum -= largest;
    return std::max(0.0, 0.5 * sum);
}

}  // namespace

double nearest_neighbor_lower_bound(std::span<const glm::dvec3> points) {
    if (points.size() < 2) return 0.0;
    return lower_bound_from(k_nearest_neighbors(points, 1), uint32_t(points.size()));
}

LevelPairing approximate_pairing(std::span<const glm::dvec3> points, const BakeStop* stop) {
    const uint32_t n = uint32_t(points.size());
    if (n < 2) {
        LevelPairing trivial;
        trivial.carried = n == 1 ? 0 : kNoCarriedNode;
        trivial.exact = true;
        return trivial;
    }

    std::vector<uint32_t> all_ids(n);
    for (uint32_t i = 0; i < n; ++i) all_ids[i] = i;
    // A stop leaves the pairing partial: the builder asks the stop and drops it.
    StopPoll poll(stop);
    const KnnResult knn = k_nearest_neighbors(points, kCandidateNeighbors, stop);
    if (poll.now()) return {};
    const std::vector<CandidateEdge> edges = candidate_edges(knn, all_ids, poll);
    if (poll()) return {};

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
        const KnnResult free_knn = k_nearest_neighbors(free_points, kRetryNeighbors, stop);
        greedy_match(candidate_edges(free_knn, free_ids, poll), mate, poll);
    }
    if (free_ids.size() == 1) {
        mate[free_ids[0]] = n;
        mate[n] = free_ids[0];
    }

    if (poll()) return {};
    two_opt(points, edges, mate, poll);
    if (poll()) return {};

    LevelPairing pairing = pairing_from_mates(points, std::span<const uint32_t>(mate).first(n));
    pairing.lower_bound = std::min(pairing.cost, lower_bound_from(knn, n));
    pairing.exact = false;
    return pairing;
}

}  // namespace lc::bake

#include "lightmass_server/builders/sparse_exact_pairing.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "lightmass_server/builders/approximate_pairing.h"
#include "lightmass_server/builders/min_weight_matching.h"
#include "lightmass_server/builders/point_kd_tree.h"

namespace lc::bake {
namespace {

uint64_t edge_key(uint32_t u, uint32_t v) {
    return (uint64_t(std::min(u, v)) << 32) | std::max(u, v);
}

// The candidate graph as sorted, unique edge keys (u < v): the edge order LEMON
// sees is a function of the edge set alone, so equal inputs give equal runs.
class CandidateGraph {
public:
    void add(uint32_t u, uint32_t v) { keys_.push_back(edge_key(u, v)); }
    void normalize() {
        std::sort(keys_.begin(), keys_.end());
        keys_.erase(std::unique(keys_.begin(), keys_.end()), keys_.end());
    }
    bool contains(uint32_t u, uint32_t v) const {
        return std::binary_search(keys_.begin(), keys_.end(), edge_key(u, v));
    }
    size_t size() const { return keys_.size(); }

    // Edges for LEMON: Euclidean costs, zero for the dummy node `real_count`.
    std::vector<MatchingEdge> edges(std::span<const glm::dvec3> points) const {
        const uint32_t real_count = uint32_t(points.size());
        std::vector<MatchingEdge> out;
        out.reserve(keys_.size());
        for (const uint64_t key : keys_) {
            const uint32_t u = uint32_t(key >> 32);
            const uint32_t v = uint32_t(key & 0xFFFFFFFFu);
            const double cost = v >= real_count ? 0.0 : glm::distance(points[u], points[v]);
            out.push_back(MatchingEdge{u, v, cost});
        }
        return out;
    }

private:
    std::vector<uint64_t> keys_;
};

// For every node, the blossoms holding it from the outermost in; the blossoms
// holding both u and v are the common prefix of their chains (laminar family).
struct BlossomChains {
    std::vector<std::vector<uint32_t>> chain;
    std::vector<double> value;

    explicit BlossomChains(const PerfectMatching& matching)
        : chain(matching.node_potential.size()) {
        std::vector<uint32_t> by_size(matching.blossoms.size());
        for (uint32_t k = 0; k < by_size.size(); ++k) by_size[k] = k;
        std::stable_sort(by_size.begin(), by_size.end(), [&](uint32_t a, uint32_t b) {
            return matching.blossoms[a].nodes.size() > matching.blossoms[b].nodes.size();
        });
        for (const uint32_t k : by_size) {
            for (const uint32_t u : matching.blossoms[k].nodes) chain[u].push_back(k);
        }
        value.reserve(matching.blossoms.size());
        for (const MatchingBlossom& b : matching.blossoms) value.push_back(b.value);
    }

    // Z_uv: the sum of z_B over blossoms B holding both u and v.
    double shared_value(uint32_t u, uint32_t v) const {
        double z = 0.0;
        const size_t common = std::min(chain[u].size(), chain[v].size());
        for (size_t i = 0; i < common && chain[u][i] == chain[v][i]; ++i) z += value[chain[u][i]];
        return z;
    }
};

struct CertificateCheck {
    std::vector<MatchingEdge> violated_outside;  // omitted edges to add
    // The rest of the proof: LEMON's dual on its own graph (including the
    // dummy's edges) and equal primal and dual objectives.
    bool holds_on_candidates = true;
};

// Reduced cost of (u, v): cost_uv + y_u + y_v + Z_uv (see min_weight_matching.h).
// Z_uv >= 0 only adds slack, so only pairs with cost_uv + y_u + y_v < -tolerance
// can violate: a kd-tree query finds them without visiting all n^2 pairs.
// With every reduced cost >= -tolerance and the objectives equal, no perfect
// matching of the complete graph costs less than this one minus
// n/2 x tolerance (weak duality).
// A stop leaves the check partial: the caller asks it and drops the check.
CertificateCheck check_certificate(std::span<const glm::dvec3> points,
                                   const PerfectMatching& matching, const CandidateGraph& graph,
                                   double tolerance, const BakeStop* stop) {
    const uint32_t n = uint32_t(points.size());
    const std::span<const double> y = std::span<const double>(matching.node_potential).first(n);
    const BlossomChains chains(matching);
    CertificateCheck check;
    // Half the tolerance: the query rounds differently, so let it return a
    // superset of the pairs the exact test below can reject.
    for (const auto& [u, v] : pairs_below_negative_offsets(points, y, 0.5 * tolerance, stop)) {
        const double cost = glm::distance(points[u], points[v]);
        if (cost + y[u] + y[v] + chains.shared_value(u, v) >= -tolerance) continue;
        if (graph.contains(u, v)) {
            check.holds_on_candidates = false;
        } else {
            check.violated_outside.push_back(MatchingEdge{u, v, cost});
        }
    }
    // The dummy's zero-cost edges (odd levels).
    if (matching.node_potential.size() > n) {
        const double y_dummy = matching.node_potential[n];
        for (uint32_t u = 0; u < n; ++u) {
            if (y[u] + y_dummy + chains.shared_value(u, n) < -tolerance) {
                check.holds_on_candidates = false;
            }
        }
    }
    // LEMON's dual objective is the maximum weight, i.e. minus the cost.
    double dual = 0.0;
    for (const double potential : matching.node_potential) dual += potential;
    for (const MatchingBlossom& b : matching.blossoms) dual += b.value * double(b.nodes.size() / 2);
    if (std::abs(matching.cost + dual) > double(n) * tolerance) check.holds_on_candidates = false;
    return check;
}

LevelPairing trivial_pairing(uint32_t n) {
    LevelPairing pairing;
    pairing.carried = n == 1 ? 0 : kNoCarriedNode;
    pairing.exact = true;
    return pairing;
}

double largest_cost(const std::vector<MatchingEdge>& edges) {
    double largest = 0.0;
    for (const MatchingEdge& e : edges) largest = std::max(largest, e.cost);
    return largest;
}

Error stopped_level(uint32_t n) {
    return make_error("exact pairing of " + std::to_string(n) + " nodes stopped",
                      ErrorKind::kCancelled);
}

// First candidate graph: k nearest neighbours, plus a feasible pairing's edges
// so a perfect matching always exists, plus the dummy's edges (odd levels).
// Returns false when the stop was asked (the graph is then partial).
bool add_first_candidates(std::span<const glm::dvec3> points, const ExactPairingOptions& options,
                          CandidateGraph& graph, LevelPairing& feasible) {
    const uint32_t n = uint32_t(points.size());
    const KnnResult knn = k_nearest_neighbors(points, options.candidate_neighbors, options.stop);
    if (stop_requested(options.stop)) return false;
    for (uint32_t u = 0; u < n; ++u) {
        for (const Neighbor& nb : knn.of(u)) graph.add(u, nb.index);
    }
    feasible = approximate_pairing(points, options.stop);
    if (stop_requested(options.stop)) return false;
    for (const auto& [u, v] : feasible.pairs) graph.add(u, v);
    if (n % 2 == 1) {
        for (uint32_t u = 0; u < n; ++u) graph.add(u, n);
    }
    graph.normalize();
    return true;
}

}  // namespace

Result<LevelPairing> exact_pairing(std::span<const glm::dvec3> points,
                                   const ExactPairingOptions& options) {
    const uint32_t n = uint32_t(points.size());
    if (n < 2) return trivial_pairing(n);
    const uint32_t node_count = n % 2 == 1 ? n + 1 : n;

    CandidateGraph graph;
    LevelPairing feasible;
    if (!add_first_candidates(points, options, graph, feasible)) return stopped_level(n);
    // LEMON asks every kWeightReadsPerStopPoll weight reads: a few ms of its work.
    StopPoll poll(options.stop);
    const MatchingStopFn should_stop =
        options.stop ? MatchingStopFn([&poll] { return poll(); }) : MatchingStopFn();

    LevelPairing pairing;
    for (uint32_t run = 1;; ++run) {
        const std::vector<MatchingEdge> edges = graph.edges(points);
        Result<PerfectMatching> matching =
            min_weight_perfect_matching(node_count, edges, should_stop);
        if (!matching && matching.error_kind() == ErrorKind::kCancelled) return stopped_level(n);
        if (!matching)
            return make_error("exact pairing of " + std::to_string(n) +
                              " nodes: " + matching.error());

        const double tolerance = 1e-9 * largest_cost(edges) + 1e-300;
        const CertificateCheck check = check_certificate(points, *matching, graph, tolerance, options.stop);
        if (poll.now()) return stopped_level(n);

        pairing = pairing_from_mates(points, matching->mate);
        pairing.solver_runs = run;
        pairing.candidate_edges = graph.size();
        if (check.violated_outside.empty()) {
            pairing.exact = check.holds_on_candidates;
            break;
        }
        if (run >= options.max_solver_runs) break;
        for (const MatchingEdge& e : check.violated_outside) graph.add(e.u, e.v);
        graph.normalize();
    }
    // An unproven level is never worse than the fast pairing it started from.
    if (!pairing.exact && feasible.cost < pairing.cost) {
        const uint32_t runs = pairing.solver_runs;
        const size_t edges = pairing.candidate_edges;
        pairing = feasible;
        pairing.solver_runs = runs;
        pairing.candidate_edges = edges;
        pairing.exact = false;
    }
    pairing.lower_bound =
        pairing.exact ? pairing.cost : std::min(pairing.cost, nearest_neighbor_lower_bound(points));
    return pairing;
}

Result<LevelPairing> exact_pairing_complete_graph(std::span<const glm::dvec3> points) {
    const uint32_t n = uint32_t(points.size());
    if (n < 2) return trivial_pairing(n);
    const bool odd = n % 2 == 1;
    std::vector<MatchingEdge> edges;
    edges.reserve(size_t(n) * (n + 1) / 2);
    for (uint32_t u = 0; u < n; ++u) {
        for (uint32_t v = u + 1; v < n; ++v) {
            edges.push_back(MatchingEdge{u, v, glm::distance(points[u], points[v])});
        }
        if (odd) edges.push_back(MatchingEdge{u, n, 0.0});
    }
    Result<PerfectMatching> matching = min_weight_perfect_matching(odd ? n + 1 : n, edges);
    if (!matching) return make_error("complete-graph pairing: " + matching.error());
    LevelPairing pairing = pairing_from_mates(points, matching->mate);
    pairing.exact = true;
    pairing.lower_bound = pairing.cost;
    pairing.solver_runs = 1;
    pairing.candidate_edges = edges.size();
    return pairing;
}

}  // namespace lc::bake

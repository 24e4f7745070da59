// Compiled as C++17: LEMON 1.3.1's array maps call std::allocator::construct,
// which C++20 removed.
#include "lightmass_server/builders/min_weight_matching.h"

// LEMON's maps default-construct graph items that are uninitialised by design;
// optimised sanitizer builds then flag LEMON's own code. Not ours to fix.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include <lemon/list_graph.h>
#include <lemon/matching.h>

#include <cmath>
#include <string>

namespace lc::bake {
namespace {

// Thrown by StopPollingWeights when asked to stop; never leaves this file.
struct MatchingStopped {};

// LEMON's weights, read through a map that asks `should_stop` every
// kWeightReadsPerStopPoll reads and unwinds the run when it says stop. Why an
// exception: the run's loop is LEMON's, with no hook but this map, and LEMON
// owns its working memory through its destructor, so unwinding frees it all.
// The weights read are the EdgeMap's own, so a run that is not stopped takes
// the same steps, and gives the same matching, as one without the poll.
class StopPollingWeights {
public:
    using Key = lemon::ListGraph::Edge;
    using Value = double;

    StopPollingWeights(const lemon::ListGraph::EdgeMap<double>& weights,
                       const MatchingStopFn& should_stop)
        : weights_(weights), should_stop_(should_stop) {}

    Value operator[](const Key& edge) const {
        if (should_stop_ && ++reads_ % kWeightReadsPerStopPoll == 0 && should_stop_()) {
            throw MatchingStopped{};
        }
        return weights_[edge];
    }

private:
    const lemon::ListGraph::EdgeMap<double>& weights_;
    const MatchingStopFn& should_stop_;
    mutable uint32_t reads_ = 0;
};

}  // namespace

Result<PerfectMatching> min_weight_perfect_matching(uint32_t node_count,
                                                    const std::vector<MatchingEdge>& edges,
                                                    const MatchingStopFn& should_stop) {
    if (node_count % 2 != 0) {
        return make_error("perfect matching needs an even node count, got " +
                          std::to_string(node_count));
    }
    PerfectMatching result;
    if (node_count == 0) return result;

    lemon::ListGraph graph;
    graph.reserveNode(int(node_count));
    graph.reserveEdge(int(edges.size()));
    std::vector<lemon::ListGraph::Node> nodes;
    nodes.reserve(node_count);
    for (uint32_t i = 0; i < node_count; ++i) nodes.push_back(graph.addNode());

    lemon::ListGraph::EdgeMap<double> weight(graph);
    for (size_t i = 0; i < edges.size(); ++i) {
        const MatchingEdge& e = edges[i];
        if (e.u >= node_count || e.v >= node_count || e.u == e.v) {
            return make_error("matching edge " + std::to_string(i) + " (" + std::to_string(e.u) +
                              ", " + std::to_string(e.v) + ") is a self-loop or out of range for " +
                              std::to_string(node_count) + " nodes");
        }
        if (!std::isfinite(e.cost)) {
            return make_error("matching edge " + std::to_string(i) + " has a non-finite cost");
        }
        const lemon::ListGraph::Edge edge = graph.addEdge(nodes[e.u], nodes[e.v]);
        weight[edge] = -e.cost;
    }

    using Matching = lemon::MaxWeightedPerfectMatching<lemon::ListGraph, StopPollingWeights>;
    const StopPollingWeights polled_weight(weight, should_stop);
    Matching matching(graph, polled_weight);
    bool matched = false;
    try {
        matched = matching.run();
    } catch (const MatchingStopped&) {
        return make_error("the matching of " + std::to_string(node_count) + " nodes was stopped",
                          ErrorKind::kCancelled);
    }
    if (!matched) {
        return make_error("the candidate graph (" + std::to_string(node_count) + " nodes, " +
                          std::to_string(edges.size()) + " edges) has no perfect matching");
    }

    result.mate.resize(node_count);
    result.node_potential.resize(node_count);
    for (uint32_t i = 0; i < node_count; ++i) {
        result.mate[i] = uint32_t(graph.id(matching.mate(nodes[i])));
        result.node_potential[i] = matching.nodeValue(nodes[i]);
    }
    for (uint32_t i = 0; i < node_count; ++i) {
        if (i < result.mate[i]) result.cost -= weight[matching.matching(nodes[i])];
    }
    result.blossoms.resize(size_t(matching.blossomNum()));
    for (int k = 0; k < matching.blossomNum(); ++k) {
        MatchingBlossom& blossom = result.blossoms[size_t(k)];
        blossom.value = matching.blossomValue(k);
        for (Matching::BlossomIt it(matching, k); it != lemon::INVALID; ++it) {
            blossom.nodes.push_back(uint32_t(graph.id(lemon::ListGraph::Node(it))));
        }
    }
    return result;
}

}  // namespace lc::bake

#pragma GCC diagnostic pop

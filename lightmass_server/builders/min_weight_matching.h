#pragma once
// Minimum-weight perfect matching (Edmonds' blossom algorithm, LEMON's
// MaxWeightedPerfectMatching on negated costs) with its dual certificate.
// This header stays C++17 so the LEMON translation unit can include it
// (LEMON 1.3.1 does not compile under C++20, SPEC §10).
#include <cstdint>
#include <functional>
#include <vector>

#include "lightcuts/result.h"

namespace lc::bake {

struct MatchingEdge {
    uint32_t u = 0;
    uint32_t v = 0;
    double cost = 0.0;
};

// One odd set of the dual solution (a blossom) and its dual value z_B >= 0.
struct MatchingBlossom {
    std::vector<uint32_t> nodes;
    double value = 0.0;
};

// LEMON solves max sum(w) with w = -cost. Its dual certificate satisfies, for
// every edge of the graph it was given,
//   y_u + y_v + sum_{B containing u and v} z_B >= w_uv = -cost_uv,
// with z_B >= 0, and equality on matched edges. An edge (u, v) outside the
// graph with  cost_uv + y_u + y_v + Z_uv >= 0  (non-negative reduced cost)
// could not improve the matching: that is the optimality proof on a larger graph.
struct PerfectMatching {
    std::vector<uint32_t> mate;             // mate[u] for every node
    double cost = 0.0;                      // sum of matched edges' costs
    std::vector<double> node_potential;     // y_u
    std::vector<MatchingBlossom> blossoms;  // laminar family of odd sets
};

// LEMON's run has no hook to stop it, and one run over a large level takes
// seconds (issue 27). Its one call into our code inside the run is the weight
// map: every kWeightReadsPerStopPoll reads, `should_stop` is asked, and true
// ends the run with an ErrorKind::kCancelled error.
inline constexpr uint32_t kWeightReadsPerStopPoll = 1024;
using MatchingStopFn = std::function<bool()>;

// Edges are added to the graph in the given order, so equal inputs give equal
// results (with or without `should_stop`: asking it never changes a weight or
// a step). Fails (naming the problem) on an out-of-range or self-loop edge, a
// non-finite cost, an odd node count, or a graph without a perfect matching.
Result<PerfectMatching> min_weight_perfect_matching(uint32_t node_count,
                                                    const std::vector<MatchingEdge>& edges,
                                                    const MatchingStopFn& should_stop = {});

}  // namespace lc::bake

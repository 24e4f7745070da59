#pragma once
// The pairing of one level of the optimal-pair builder: which nodes of the
// level merge, which one (odd levels) is carried up unpaired, and what it cost.
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

namespace lc::bake {

inline constexpr uint32_t kNoCarriedNode = std::numeric_limits<uint32_t>::max();

struct LevelPairing {
    // Indices into the level, first < second within a pair, pairs sorted.
    std::vector<std::pair<uint32_t, uint32_t>> pairs;
    uint32_t carried = kNoCarriedNode;  // set exactly when the level is odd
    double cost = 0.0;                  // sum of the pairs' Euclidean distances
    double lower_bound = 0.0;           // of the optimal cost; == cost when exact
    bool exact = false;
    // Diagnostics of the exact solver: LEMON runs and final candidate edges.
    uint32_t solver_runs = 0;
    size_t candidate_edges = 0;
};

// Turns a mate array over the level (+ one dummy node `level_size` for odd
// levels) into sorted pairs, the carried node, and the Euclidean cost.
inline LevelPairing pairing_from_mates(std::span<const glm::dvec3> points,
                                       std::span<const uint32_t> mate) {
    LevelPairing pairing;
    const uint32_t n = uint32_t(points.size());
    for (uint32_t u = 0; u < n; ++u) {
        const uint32_t v = mate[u];
        if (v >= n) {
            pairing.carried = u;
        } else if (u < v) {
            pairing.pairs.emplace_back(u, v);
            pairing.cost += glm::distance(points[u], points[v]);
        }
    }
    return pairing;
}

}  // namespace lc::bake

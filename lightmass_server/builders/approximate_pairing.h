#pragma once
// A fast pairing of one level for sizes where the exact matching is too slow:
// greedy on k-nearest-neighbour candidate edges, then 2-opt exchanges, with a
// lower bound of the optimum so the report can state the worst-case gap.
#include <glm/vec3.hpp>

#include <span>

#include "lightmass_server/control/bake_stop.h"
#include "lightmass_server/builders/level_pairing.h"

namespace lc::bake {

// Pairs every point (one carried up unpaired when the count is odd). The lower
// bound: in any pairing, a paired point u pays at least nn(u) / 2 of its edge,
// where nn(u) is its nearest-neighbour distance, so
//   optimum >= (sum_u nn(u) - [odd] max_u nn(u)) / 2.
LevelPairing approximate_pairing(std::span<const glm::dvec3> points, const BakeStop* stop = nullptr);

// The lower bound above on its own (used by the exact path's tests too).
double nearest_neighbor_lower_bound(std::span<const glm::dvec3> points);

}  // namespace lc::bake

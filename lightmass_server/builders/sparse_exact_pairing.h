#pragma once
// The exact minimum-cost pairing of one level, without building the complete
// graph: solve on a sparse candidate graph (k nearest neighbours, a feasible
// pairing's edges, and the dummy's zero-cost edges for odd levels), then check
// LEMON's dual certificate against EVERY edge of the complete graph. Edges with
// negative reduced cost join the candidate graph and the level is solved again,
// until none remain; only then is the level exact (SPEC §4).
#include <glm/vec3.hpp>

#include <span>

#include "lightmass_server/control/bake_stop.h"
#include "lightmass_server/builders/level_pairing.h"
#include "lightcuts/result.h"

namespace lc::bake {

struct ExactPairingOptions {
    // Nearest neighbours per point in the first candidate graph.
    uint32_t candidate_neighbors = 10;
    // Re-solves allowed before giving up on the proof (the level is then
    // reported as inexact with a lower bound); each adds all violating edges.
    uint32_t max_solver_runs = 32;
    // Polled in every step of the level, LEMON's runs included (issue 27);
    // a stopped level returns ErrorKind::kCancelled. Null: never stops.
    const BakeStop* stop = nullptr;
};

// Odd levels carry one node up, chosen optimally: a dummy node joins the graph
// with a zero-cost edge to every node, and its mate is carried.
// Costs are Euclidean distances. The proof accepts reduced costs down to
// -tol = -1e-9 x (the largest candidate edge cost), the scale of LEMON's
// rounding, so "exact" means: no pairing is cheaper by more than n/2 x tol.
Result<LevelPairing> exact_pairing(std::span<const glm::dvec3> points,
                                   const ExactPairingOptions& options = {});

// LEMON on the complete graph: the reference the sparse solver must match
// (quadratic memory and much slower; tests only).
Result<LevelPairing> exact_pairing_complete_graph(std::span<const glm::dvec3> points);

}  // namespace lc::bake

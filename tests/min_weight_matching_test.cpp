// Exact pairing: LEMON's matching and its dual certificate, brute force for
// small levels, and the sparse candidate graph + proof against the complete graph.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "lightmass_server/builders/approximate_pairing.h"
#include "lightmass_server/builders/min_weight_matching.h"
#include "lightmass_server/builders/point_kd_tree.h"
#include "lightmass_server/builders/sparse_exact_pairing.h"

namespace lc::bake {
namespace {

std::vector<glm::dvec3> random_points(uint32_t n, uint64_t seed, double extent = 100.0) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, extent);
    std::vector<glm::dvec3> points(n);
    for (auto& p : points) p = glm::dvec3(unit(rng), unit(rng), unit(rng));
    return points;
}

// Tight clusters of 5 points around far-apart centres.
std::vector<glm::dvec3> clustered_points(uint32_t n, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> centre(0.0, 1000.0), jitter(-1.0, 1.0);
    std::vector<glm::dvec3> points;
    glm::dvec3 c(0.0);
    for (uint32_t i = 0; i < n; ++i) {
        if (i % 5 == 0) c = glm::dvec3(centre(rng), centre(rng), centre(rng));
        points.push_back(c + glm::dvec3(jitter(rng), jitter(rng), jitter(rng)));
    }
    return points;
}

// A regular grid: many equal distances, the tie-breaking case.
std::vector<glm::dvec3> grid_points(uint32_t nx, uint32_t ny, uint32_t nz) {
    std::vector<glm::dvec3> points;
    for (uint32_t z = 0; z < nz; ++z)
        for (uint32_t y = 0; y < ny; ++y)
            for (uint32_t x = 0; x < nx; ++x) points.emplace_back(x, y, z);
    return points;
}

// The minimum over every way to carry one node (odd) and perfectly match the
// rest. Enumerates by always pairing the lowest unpaired node; depth <= 6.
double brute_force_cost(const std::vector<glm::dvec3>& points) {
    const uint32_t n = uint32_t(points.size());
    double best = std::numeric_limits<double>::infinity();
    std::vector<bool> used(n, false);
    auto search = [&](auto&& self, double cost) -> void {
        uint32_t first = 0;
        while (first < n && used[first]) ++first;
        if (first == n) {
            best = std::min(best, cost);
            return;
        }
        used[first] = true;
        for (uint32_t v = first + 1; v < n; ++v) {
            if (used[v]) continue;
            used[v] = true;
            self(self, cost + glm::distance(points[first], points[v]));
            used[v] = false;
        }
        used[first] = false;
    };
    if (n % 2 == 0) {
        search(search, 0.0);
    } else {
        for (uint32_t carried = 0; carried < n; ++carried) {
            used[carried] = true;
            search(search, 0.0);
            used[carried] = false;
        }
    }
    return best;
}

// Every node appears exactly once: in one pair, or carried (odd levels only).
void expect_valid_pairing(const LevelPairing& pairing, uint32_t n) {
    std::vector<int> seen(n, 0);
    for (const auto& [a, b] : pairing.pairs) {
        ASSERT_LT(a, b);
        ASSERT_LT(b, n);
        ++seen[a];
        ++seen[b];
    }
    if (n % 2 == 1) {
        ASSERT_LT(pairing.carried, n);
        ++seen[pairing.carried];
    } else {
        EXPECT_EQ(pairing.carried, kNoCarriedNode);
    }
    for (uint32_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << "node " << i;
}

TEST(MinWeightMatching, SolvesASmallGraphWithAValidDualCertificate) {
    // A 6-cycle with chords; costs chosen so the optimum is unique: (0,1)(2,3)(4,5).
    const std::vector<MatchingEdge> edges = {{0, 1, 1.0}, {1, 2, 5.0}, {2, 3, 1.5}, {3, 4, 4.0},
                                             {4, 5, 2.0}, {5, 0, 6.0}, {0, 3, 3.0}, {1, 4, 7.0}};
    Result<PerfectMatching> m = min_weight_perfect_matching(6, edges);
    ASSERT_TRUE(m) << m.error();
    EXPECT_EQ(m->mate, (std::vector<uint32_t>{1, 0, 3, 2, 5, 4}));
    EXPECT_DOUBLE_EQ(m->cost, 4.5);
    // Dual feasibility on every edge, equality on matched edges, equal objectives.
    auto shared = [&](uint32_t u, uint32_t v) {
        double z = 0.0;
        for (const auto& b : m->blossoms) {
            const bool hu = std::count(b.nodes.begin(), b.nodes.end(), u) > 0;
            const bool hv = std::count(b.nodes.begin(), b.nodes.end(), v) > 0;
            if (hu && hv) z += b.value;
        }
        return z;
    };
    for (const MatchingEdge& e : edges) {
        const double reduced =
            e.cost + m->node_potential[e.u] + m->node_potential[e.v] + shared(e.u, e.v);
        EXPECT_GE(reduced, -1e-12);
        if (m->mate[e.u] == e.v) {
            EXPECT_NEAR(reduced, 0.0, 1e-12);
        }
    }
    double dual = 0.0;
    for (double y : m->node_potential) dual += y;
    for (const auto& b : m->blossoms) dual += b.value * double(b.nodes.size() / 2);
    EXPECT_NEAR(-dual, m->cost, 1e-12);
}

TEST(MinWeightMatching, DualCertificateHoldsWithBlossoms) {
    // Two triangles joined by an expensive edge force odd-set duals.
    const std::vector<MatchingEdge> edges = {{0, 1, 1.0}, {1, 2, 1.0}, {0, 2, 1.0}, {3, 4, 1.0},
                                             {4, 5, 1.0}, {3, 5, 1.0}, {2, 3, 10.0}};
    Result<PerfectMatching> m = min_weight_perfect_matching(6, edges);
    ASSERT_TRUE(m) << m.error();
    EXPECT_DOUBLE_EQ(m->cost, 12.0);
    EXPECT_EQ(m->mate[2], 3u);
    double dual = 0.0;
    for (double y : m->node_potential) dual += y;
    for (const auto& b : m->blossoms) {
        EXPECT_GE(b.value, -1e-12);
        EXPECT_EQ(b.nodes.size() % 2, 1u);
        dual += b.value * double(b.nodes.size() / 2);
    }
    EXPECT_NEAR(-dual, m->cost, 1e-12);
}

TEST(MinWeightMatching, RejectsBadInputWithAMessage) {
    EXPECT_FALSE(min_weight_perfect_matching(3, {{0, 1, 1.0}}));
    Result<PerfectMatching> loop = min_weight_perfect_matching(2, {{1, 1, 1.0}});
    ASSERT_FALSE(loop);
    EXPECT_NE(loop.error().find("self-loop"), std::string::npos);
    EXPECT_FALSE(min_weight_perfect_matching(2, {{0, 2, 1.0}}));
    EXPECT_FALSE(min_weight_perfect_matching(2, {{0, 1, std::nan("")}}));
    Result<PerfectMatching> none = min_weight_perfect_matching(4, {{0, 1, 1.0}, {0, 2, 1.0}});
    ASSERT_FALSE(none);
    EXPECT_NE(none.error().find("no perfect matching"), std::string::npos);
    Result<PerfectMatching> empty = min_weight_perfect_matching(0, {});
    ASSERT_TRUE(empty);
    EXPECT_TRUE(empty->mate.empty());
}

// A level's first candidate graph as exact_pairing builds it: 10 nearest
// neighbours and a feasible pairing's edges, sorted and unique.
std::vector<MatchingEdge> candidate_edges(const std::vector<glm::dvec3>& points) {
    std::vector<std::pair<uint32_t, uint32_t>> keys;
    const KnnResult knn = k_nearest_neighbors(points, 10);
    for (uint32_t u = 0; u < points.size(); ++u) {
        for (const Neighbor& nb : knn.of(u)) keys.emplace_back(std::min(u, nb.index), std::max(u, nb.index));
    }
    for (const auto& pair : approximate_pairing(points).pairs) keys.push_back(pair);
    std::sort(keys.begin(), keys.end());
    keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
    std::vector<MatchingEdge> edges;
    for (const auto& [u, v] : keys) edges.push_back({u, v, glm::distance(points[u], points[v])});
    return edges;
}

// Issue 27: LEMON's run over a large level is stopped from inside, at the
// first poll after the stop is asked (at most kWeightReadsPerStopPoll weight
// reads later), and a run that is polled but never stopped is unchanged.
TEST(MinWeightMatching, AStopEndsTheRunAtThePollThatAskedAndPollingChangesNothing) {
    const std::vector<glm::dvec3> points = random_points(6000, 27);
    const std::vector<MatchingEdge> edges = candidate_edges(points);
    Result<PerfectMatching> plain = min_weight_perfect_matching(6000, edges);
    ASSERT_TRUE(plain) << plain.error();

    uint64_t polls = 0;
    Result<PerfectMatching> polled = min_weight_perfect_matching(6000, edges, [&] { return ++polls == 0; });
    ASSERT_TRUE(polled) << polled.error();
    EXPECT_EQ(polled->mate, plain->mate);
    EXPECT_EQ(polled->node_potential, plain->node_potential);
    EXPECT_EQ(polled->blossoms.size(), plain->blossoms.size());
    EXPECT_EQ(polled->cost, plain->cost);
    // Polled throughout the run: its work between two polls is a small part of it.
    ASSERT_GT(polls, 200u);

    for (const uint64_t stop_at : {uint64_t(1), polls / 2, polls - 1}) {
        uint64_t asked = 0;
        Result<PerfectMatching> stopped =
            min_weight_perfect_matching(6000, edges, [&] { return ++asked >= stop_at; });
        ASSERT_FALSE(stopped) << "stopped at poll " << stop_at;
        EXPECT_EQ(stopped.error_kind(), ErrorKind::kCancelled);
        EXPECT_NE(stopped.error().find("stopped"), std::string::npos) << stopped.error();
        EXPECT_EQ(asked, stop_at);  // no poll after the one that said stop
    }
}

TEST(ExactPairing, AStoppedLevelReturnsCancelledAndALiveStopChangesNothing) {
    const std::vector<glm::dvec3> points = random_points(3001, 28);
    BakeStop live;
    Result<LevelPairing> with_stop = exact_pairing(points, {.stop = &live});
    Result<LevelPairing> without = exact_pairing(points);
    ASSERT_TRUE(with_stop && without);
    EXPECT_EQ(with_stop->pairs, without->pairs);
    EXPECT_EQ(with_stop->carried, without->carried);
    EXPECT_TRUE(with_stop->exact);

    BakeStop cancelled;
    cancelled.cancel();
    Result<LevelPairing> stopped = exact_pairing(points, {.stop = &cancelled});
    ASSERT_FALSE(stopped);
    EXPECT_EQ(stopped.error_kind(), ErrorKind::kCancelled);
    EXPECT_NE(stopped.error().find("exact pairing of 3001 nodes stopped"), std::string::npos)
        << stopped.error();
}

TEST(ExactPairing, MatchesBruteForceForEverySizeUpToTen) {
    for (uint32_t n = 1; n <= 10; ++n) {
        for (uint64_t seed = 1; seed <= 6; ++seed) {
            const std::vector<glm::dvec3> points = random_points(n, seed * 97 + n);
            Result<LevelPairing> exact = exact_pairing(points);
            ASSERT_TRUE(exact) << exact.error();
            expect_valid_pairing(*exact, n);
            EXPECT_TRUE(exact->exact);
            const double best = brute_force_cost(points);
            EXPECT_NEAR(exact->cost, best, 1e-9 * (1.0 + best)) << "n=" << n << " seed=" << seed;
            EXPECT_DOUBLE_EQ(exact->lower_bound, exact->cost);
            // The fast pairing is never better than the optimum, its bound never above.
            const LevelPairing approx = approximate_pairing(points);
            expect_valid_pairing(approx, n);
            EXPECT_GE(approx.cost, best - 1e-9 * (1.0 + best));
            EXPECT_LE(approx.lower_bound, best + 1e-9 * (1.0 + best));
        }
    }
}

TEST(ExactPairing, ProofLoopRepairsATooSparseCandidateGraph) {
    // With one neighbour per point the first candidate graph usually misses
    // optimal edges; the dual check must add them until the optimum is reached.
    uint32_t levels_needing_more_runs = 0;
    for (uint64_t seed = 1; seed <= 8; ++seed) {
        const std::vector<glm::dvec3> points = random_points(120 + uint32_t(seed % 2), seed);
        Result<LevelPairing> sparse = exact_pairing(points, {.candidate_neighbors = 1});
        Result<LevelPairing> complete = exact_pairing_complete_graph(points);
        ASSERT_TRUE(sparse && complete);
        EXPECT_TRUE(sparse->exact);
        EXPECT_NEAR(sparse->cost, complete->cost, 1e-9 * complete->cost);
        if (sparse->solver_runs > 1) ++levels_needing_more_runs;
    }
    EXPECT_GT(levels_needing_more_runs, 0u);
}

TEST(ExactPairing, SparseProofEqualsCompleteGraphOnRandomClusteredAndGridSets) {
    std::vector<std::vector<glm::dvec3>> sets;
    for (uint64_t seed = 1; seed <= 3; ++seed)
        sets.push_back(random_points(200 + uint32_t(seed % 2), seed));
    for (uint64_t seed = 1; seed <= 2; ++seed)
        sets.push_back(clustered_points(200 + uint32_t(seed % 2), seed));
    sets.push_back(grid_points(10, 10, 2));  // 200 points, many ties
    sets.push_back(grid_points(7, 7, 4));    // 196
    sets.push_back(grid_points(199, 1, 1));  // a line, odd
    std::vector<glm::dvec3> coincident(101, glm::dvec3(3.0, -2.0, 1.0));
    sets.push_back(coincident);
    for (size_t s = 0; s < sets.size(); ++s) {
        Result<LevelPairing> sparse = exact_pairing(sets[s]);
        Result<LevelPairing> complete = exact_pairing_complete_graph(sets[s]);
        ASSERT_TRUE(sparse) << sparse.error();
        ASSERT_TRUE(complete) << complete.error();
        expect_valid_pairing(*sparse, uint32_t(sets[s].size()));
        EXPECT_TRUE(sparse->exact) << "set " << s;
        EXPECT_NEAR(sparse->cost, complete->cost, 1e-9 * (1.0 + complete->cost)) << "set " << s;
        EXPECT_LT(sparse->candidate_edges, complete->candidate_edges / 4) << "set " << s;
    }
}

TEST(ExactPairing, IsDeterministicWithTies) {
    const std::vector<glm::dvec3> grid = grid_points(16, 16, 1);
    Result<LevelPairing> a = exact_pairing(grid);
    Result<LevelPairing> b = exact_pairing(grid);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->pairs, b->pairs);
    EXPECT_EQ(a->carried, b->carried);
    EXPECT_DOUBLE_EQ(a->cost, 128.0);  // 256 grid points, unit pairs
}

TEST(PointKdTree, OffsetPairQueryMatchesBruteForce) {
    // The certificate check's pruned query must return exactly the pairs with
    // |p_u - p_v| + o_u + o_v < -tolerance.
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> offset(-40.0, 5.0);
    for (const auto& points : {random_points(300, 1), clustered_points(301, 2)}) {
        std::vector<double> o(points.size());
        for (double& x : o) x = offset(rng);
        std::vector<std::pair<uint32_t, uint32_t>> expected;
        for (uint32_t u = 0; u < points.size(); ++u) {
            for (uint32_t v = u + 1; v < points.size(); ++v) {
                if (glm::distance(points[u], points[v]) + o[u] + o[v] < -1e-6) {
                    expected.emplace_back(u, v);
                }
            }
        }
        EXPECT_GT(expected.size(), 10u);
        EXPECT_EQ(pairs_below_negative_offsets(points, o, 1e-6), expected);
    }
}

TEST(PointKdTree, NearestNeighborsMatchBruteForce) {
    const std::vector<glm::dvec3> points = grid_points(6, 5, 4);  // many equal distances
    const KnnResult knn = k_nearest_neighbors(points, 7);
    ASSERT_EQ(knn.k_used, 7u);
    for (uint32_t u = 0; u < points.size(); ++u) {
        std::vector<std::pair<double, uint32_t>> all;
        for (uint32_t v = 0; v < points.size(); ++v) {
            if (v != u) all.emplace_back(glm::distance(points[u], points[v]), v);
        }
        std::sort(all.begin(), all.end());
        for (uint32_t j = 0; j < 7; ++j) {
            EXPECT_EQ(knn.of(u)[j].index, all[j].second) << "point " << u << " rank " << j;
        }
    }
}

TEST(ApproximatePairing, StaysWithinItsLowerBoundGap) {
    const std::vector<glm::dvec3> points = random_points(2001, 5);
    Result<LevelPairing> exact = exact_pairing(points);
    ASSERT_TRUE(exact);
    const LevelPairing approx = approximate_pairing(points);
    expect_valid_pairing(approx, 2001);
    EXPECT_FALSE(approx.exact);
    EXPECT_LE(approx.lower_bound, exact->cost);
    EXPECT_GE(approx.cost, exact->cost * (1 - 1e-12));
    // A greedy + 2-opt pairing of uniform points stays within 25% of the optimum.
    EXPECT_LT(approx.cost, 1.25 * exact->cost);
    EXPECT_GT(approx.lower_bound, 0.5 * exact->cost);
    std::printf("2001 points: exact %.3f, approximate %.3f (+%.2f%%), lower bound %.3f\n",
                exact->cost, approx.cost, 100.0 * (approx.cost / exact->cost - 1.0),
                approx.lower_bound);
}

}  // namespace
}  // namespace lc::bake

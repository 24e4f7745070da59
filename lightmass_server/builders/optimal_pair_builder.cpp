#include "lightmass_server/builders/optimal_pair_builder.h"

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "lightmass_server/builders/approximate_pairing.h"
#include "lightmass_server/builders/build_phase_timer.h"
#include "lightmass_server/builders/cluster_attributes.h"
#include "lightmass_server/builders/sparse_exact_pairing.h"
#include "lightmass_server/builders/stoppable_sort.h"

namespace lc::bake {
namespace {

std::string format_double(double value) {
    char text[64];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

bool pair_exactly(const BuildOptions& options, size_t level_size) {
    switch (options.pairing) {
        case PairingMode::kExact: return true;
        case PairingMode::kApproximate: return false;
        case PairingMode::kAuto: break;
    }
    return level_size <= options.exact_pairing_limit;
}

// The level's exact pairing; a level that could not be proven optimal is
// reported, a stopped one ends the build as cancelled.
Result<LevelPairing> pair_level_exactly(std::span<const glm::dvec3> points, const BuildOptions& options,
                                        uint32_t level_number, LightType type, BuildReport& report) {
    Result<LevelPairing> exact = exact_pairing(points, {.stop = options.stop});
    if (!exact && exact.error_kind() == ErrorKind::kCancelled) {
        return make_error("cancelled during optimal-pair level " + std::to_string(level_number) +
                              " (exact pairing)",
                          ErrorKind::kCancelled);
    }
    if (!exact) return make_error(exact.error());
    if (!exact->exact) {
        report.warnings.push_back(
            std::string("optimal-pair: the exact pairing of level ") + std::to_string(level_number) +
            " (" + std::to_string(points.size()) + " " + light_type_name(type) +
            " nodes) could not be proven optimal; cost " + format_double(exact->cost) +
            ", lower bound " + format_double(exact->lower_bound));
    }
    return exact;
}

// The level's points (its representatives' positions), asking the stop every
// 65,536 (a first level gathers millions); false when it came.
bool gather_points(const BuildArena& arena, const std::vector<uint32_t>& level, const BakeStop* stop,
                   std::vector<glm::dvec3, UnwrittenOnResize<glm::dvec3>>& points) {
    points.resize(level.size());
    StopPoll poll(stop);
    for (size_t i = 0; i < level.size(); ++i) {
        if ((i & 0xFFFFu) == 0xFFFFu && poll.now()) return false;
        points[i] = light_point(arena.lights[arena.representative_of(level[i])]);
    }
    return true;
}

}  // namespace

Result<int32_t> build_optimal_pair_tree(BuildArena& arena, std::span<const uint32_t> leaves,
                                        const BuildOptions& options,
                                        const BuildProgressFn& progress, BuildReport& report) {
    if (leaves.empty()) return kNoChild;
    BuildPhaseTimer timer(report);
    const LightType type = arena.lights[leaves[0]].type;

    std::vector<uint32_t> level(leaves.begin(), leaves.end());
    std::vector<uint32_t> next;
    // Not zeroed when sized (96 MiB for 4 M leaves, before the first poll): the gather writes each.
    std::vector<glm::dvec3, UnwrittenOnResize<glm::dvec3>> points;
    // Work is proportional to the nodes paired: n + n/2 + ... < 2n.
    const double total_work = 2.0 * double(leaves.size());
    double done_work = 0.0;
    uint32_t level_number = 0;

    while (level.size() > 1) {
        if (!gather_points(arena, level, options.stop, points))
            return make_error("cancelled during optimal-pair level " + std::to_string(level_number),
                              ErrorKind::kCancelled);

        LevelPairing pairing;
        if (pair_exactly(options, level.size())) {
            Result<LevelPairing> exact = pair_level_exactly(points, options, level_number, type, report);
            if (!exact) return exact.failure();
            pairing = std::move(*exact);
        } else {
            pairing = approximate_pairing(points, options.stop);  // stopped: no pairs, caught below
            if (options.pairing == PairingMode::kAuto) {
                report.warnings.push_back(
                    std::string("optimal-pair: level ") + std::to_string(level_number) + " has " +
                    std::to_string(level.size()) + " " + light_type_name(type) +
                    " nodes, above the exact pairing limit " +
                    std::to_string(options.exact_pairing_limit) + ": paired approximately (cost " +
                    format_double(pairing.cost) + ", lower bound " +
                    format_double(pairing.lower_bound) + ")");
            }
        }
        report.pairing_cost += pairing.cost;
        report.pairing_lower_bound += pairing.lower_bound;
        report.exact = report.exact && pairing.exact;

        next.clear();
        StopPoll poll(options.stop);
        for (const auto& [a, b] : pairing.pairs) {
            if (poll()) break;
            const BuildNode cluster = merge_clusters(arena, level[a], level[b],
                                                     options.representative_rule, options.seed);
            next.push_back(uint32_t(arena.nodes.size()));
            arena.nodes.push_back(cluster);
        }
        if (stop_requested(options.stop))
            return make_error("cancelled during optimal-pair level " + std::to_string(level_number),
                              ErrorKind::kCancelled);
        if (pairing.carried != kNoCarriedNode) next.push_back(level[pairing.carried]);
        // Clusters are disjoint, so their smallest light indices are distinct: a
        // total order, and 2 M lookups into the arena that a stop may cut short.
        const bool ordered = stoppable_sort(std::span<uint32_t>(next), [&](uint32_t a, uint32_t b) {
            return arena.min_light_index_of(a) < arena.min_light_index_of(b);
        }, poll);
        if (!ordered)
            return make_error("cancelled during optimal-pair level " + std::to_string(level_number),
                              ErrorKind::kCancelled);

        done_work += double(level.size());
        ++level_number;
        if (progress && !progress(std::min(1.0, done_work / total_work))) {
            return make_error("cancelled during optimal-pair level " +
                              std::to_string(level_number - 1), ErrorKind::kCancelled);
        }
        level.swap(next);
    }
    report.levels = std::max(report.levels, level_number);
    timer.lap("optimal-pair: levels");
    return int32_t(level[0]);
}

}  // namespace lc::bake

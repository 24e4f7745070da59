#include "lightcuts/cuts/bound_walk.h"

#include <algorithm>
#include <limits>
#include <utility>

#include "lightcuts/cuts/cut_traversal.h"
#include "lightcuts/device/walk_schedule.glsl.h"

namespace lc {
namespace {

struct Pass {
    CutTally cut;
    double worst = 0.0;  // largest bound among the cut's non-leaf nodes
    std::vector<int32_t> nodes;  // the cut's node indices, when asked for
};

// The cut of every node whose bound exceeds tau refined (mixed-type junctions
// always). The cut is a function of tau alone, so the walk's order does not
// matter; the shader walks in pre-order.
Pass walk_pass(const WalkTree& tree, const SurfacePoint& p, const CutSettings& settings, double tau,
               bool keep_nodes) {
    Pass pass;
    pass.cut = walk_cut(tree, p, settings, [&](int32_t index, const GpuTreeNode& node, int child_count) {
        const double key = error_key(tree, index, p);
        const bool refine = child_count > 0 && (joins_types(node) || key > tau);
        if (!refine) {
            pass.worst = std::max(pass.worst, key);
            if (keep_nodes) pass.nodes.push_back(index);
        }
        return refine;
    });
    return pass;
}

}  // namespace

double bisection_threshold(double fit_hi, double over_lo) {
    return device::bisection_threshold(fit_hi, over_lo);
}

CutResult bound_walk_cut(const WalkTree& tree, const SurfacePoint& p, const CutSettings& settings,
                         std::vector<CutNodeEstimate>* nodes) {
    CutResult result;
    if (tree.empty()) return result;
    std::vector<int32_t> kept;  // the nodes of the pass whose cut the result holds
    // Shaded again only when asked for: the walk tallies its nodes without keeping them.
    const auto append_kept = [&] {
        if (nodes == nullptr) return;
        for (int32_t index : kept) nodes->push_back({index, shade_cluster(tree, index, p, settings)});
    };
    const BoundRule rule(settings);
    double tau = std::numeric_limits<double>::infinity();
    bool bisecting = false;
    double fit_hi = 0.0;   // largest bound on the last cut that fit: any tau >= it gives that cut
    double over_lo = 0.0;  // a tau whose cut exceeded max_cut
    uint32_t bisections_left = kWalkBisections;
    for (uint32_t pass_index = 0; pass_index < kWalkMaxPasses; ++pass_index) {
        Pass pass = walk_pass(tree, p, settings, tau, nodes != nullptr);
        result.passes = pass_index + 1;
        // Pass 0 is the per-type roots and always kept, whatever max_cut says.
        if (pass_index > 0 && pass.cut.size > rule.max_cut) {
            bisecting = true;
            over_lo = tau;
        } else {
            pass.cut.copy_to(result, indirect_clamp_ratio(settings.error_ratio));
            kept = std::move(pass.nodes);
            // The rule reads the clamped total (device/indirect_clamp.glsl.h).
            const double limit = rule.limit(result.radiance);
            if (!(pass.worst > limit)) {  // the rule holds: not a max-cut hit
                append_kept();
                return result;
            }
            fit_hi = pass.worst;
            if (!bisecting) {
                tau = device::next_walk_threshold(limit, pass.worst, kWalkMargin, kWalkShrink);
                continue;
            }
        }
        if (bisections_left == 0) break;
        --bisections_left;
        tau = bisection_threshold(fit_hi, over_lo);
    }
    result.max_cut_hit = true;  // stopped by max_cut, or still refining after the last pass
    append_kept();
    return result;
}

}  // namespace lc

#include "editor_client/render/gpu/loop_budget.h"

#include <algorithm>
#include <string>

#include "lightcuts/device/limits.h"

namespace lc::client {
namespace {

// Worst-case loop iterations of one shadow ray: every wide node and leaf once.
uint64_t shadow_ray_iterations(const LoopWork& work) {
    if (work.shadow_bvh == nullptr || work.shadow_bvh->empty()) return 0;
    return (uint64_t(work.shadow_bvh->walk_steps()) + kShadowUnroll - 1) / kShadowUnroll + 1;
}

// The classic lights' loop, with a ray per light (`ray` iterations each).
uint64_t classic_iterations(uint32_t classic_count, uint64_t ray) {
    return (uint64_t(classic_count) + kLoopUnroll - 1) / kLoopUnroll + 1 +
           uint64_t(classic_count) * ray;
}

}  // namespace

uint32_t reference_chunk(const vk::DeviceQuirks& quirks, const LoopWork& work) {
    const uint32_t all = std::max(work.leaf_count, 1u);
    if (!quirks.has_loop_limit()) return all;
    const uint64_t budget = quirks.loop_iteration_limit;
    const uint64_t ray = shadow_ray_iterations(work);
    const uint64_t classic = classic_iterations(work.classic_count, ray);
    // Per group of kLoopUnroll leaves: one iteration and their rays; the
    // remainder loop may add kLoopUnroll - 1 single leaves.
    const uint64_t per_group = 1 + kLoopUnroll * ray;
    const uint64_t tail = (kLoopUnroll - 1) * (1 + ray) + 2;
    if (classic + tail + per_group > budget) return kLoopUnroll;  // refused by the check
    const uint64_t groups = (budget - classic - tail) / per_group;
    return uint32_t(std::min<uint64_t>(all, groups * kLoopUnroll));
}

Status check_loop_budget(const vk::DeviceQuirks& quirks, const LoopWork& work,
                         const RenderSettings& settings) {
    if (!quirks.has_loop_limit()) return Ok{};
    const uint64_t ray = shadow_ray_iterations(work);
    uint64_t iterations = classic_iterations(work.classic_count, ray);
    std::string what;
    if (settings.mode == RenderMode::kReference) {
        // Without tree lights the leaf loops trace no ray: a scene without
        // lights renders its emission (or black), however large its BVH.
        const uint64_t leaf_ray = work.leaf_count > 0 ? ray : 0;
        iterations += 1 + kLoopUnroll * leaf_ray + (kLoopUnroll - 1) * (1 + leaf_ray) + 2;
        what = std::to_string(work.classic_count) + " classic lights" +
               (ray > 0 ? " with shadow rays" : "") + " in reference mode";
    } else if (settings.criterion == CutCriterion::kRadius) {
        iterations += (uint64_t(work.node_count) + kRadiusUnroll - 1) / kRadiusUnroll + 1;
        what = "a radius-criterion walk of " + std::to_string(work.node_count) + " nodes";
    } else if (settings.bound_search == BoundSearch::kWalk) {
        // A pass the limit cut short (its walk did not reach the end of the
        // tree, or a ray did not finish) runs again in the next dispatch; one
        // that alone exceeds the limit is discarded, the pixel keeping its
        // last complete pass and counted in loop_limit_stops: nothing is
        // truncated silently, so nothing to refuse.
        return Ok{};
    } else {
        // Per refinement: a heap pop and two pushes (log2 K each), two children
        // with an 8-corner bound each; then the final sum over the heap.
        uint64_t k = settings.max_cut, log_k = 1;
        while ((uint64_t(1) << log_k) < k + 1) ++log_k;
        iterations += k * (3 * log_k + 2 * 8 + 4) + k;
        what = "the bound criterion with max cut " + std::to_string(settings.max_cut);
    }
    const uint64_t budget = quirks.loop_iteration_limit;
    if (iterations <= budget) return Ok{};
    return make_error(what + " needs about " + std::to_string(iterations) +
                      " shader loop iterations per pixel; llvmpipe (lavapipe) silently stops loops after " +
                      std::to_string(budget) +
                      ", so this render is refused rather than truncated: use fewer lights, a smaller "
                      "--max-cut, the bound criterion, or a GPU");
}

}  // namespace lc::client

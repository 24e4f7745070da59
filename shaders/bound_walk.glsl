// The bound criterion's walk search (lightcuts/cuts/bound_walk.h) for one pixel,
// shared by lightcuts_bound_walk.comp and reconstruction cuts
// (lightcuts_reconstruction_samples.comp runs it at the samples and records
// each kept cut under LC_WALK_RECORDS; lightcuts_reconstruction_pixels.comp
// runs it where a pixel falls back). The search itself is described in
// lightcuts_bound_walk.comp.
#ifndef LC_BOUND_WALK_GLSL
#define LC_BOUND_WALK_GLSL

#include "bound_criterion.glsl"
#include "lightcuts/device/walk_schedule.glsl.h"

// The walk search's max-cut and pass schedule (bound_walk.h).
layout(constant_id = kSpecWalkMaxCut) const uint kWalkMaxCut = 1000u;
layout(constant_id = kSpecWalkMaxPasses) const uint kWalkMaxPasses = 12u;
layout(constant_id = kSpecWalkShrink) const float kWalkShrink = 512.0;
layout(constant_id = kSpecWalkMargin) const float kWalkMargin = 0.8;
layout(constant_id = kSpecWalkBisections) const uint kWalkBisections = 6u;
layout(constant_id = kSpecWalkShareCuts) const bool kWalkShareCuts = false;

// One threshold pass of one lane.
struct WalkPass {
    vec3 radiance;  // f_r already applied
    uint size;
    uint hash;
    float worst;    // largest bound among the cut's non-leaf nodes
    bool over;      // the cut would exceed max-cut: the pass is abandoned
    IndirectSums indirect;  // the cut's indirect nodes, for the clamp
};

// One step of a pass; like radius_walk_step, the subgroup shares the walk and
// a lane that takes a node as a cluster waits for the walk to leave its
// subtree. A lane sitting the pass out (done, or over max-cut) waits for
// kEndOfWalk, which no node index equals.
// `shade` false: only sizes the cut (no light is evaluated, no ray traced).
// `share` false: this lane refines by its own bound alone (kWalkAlone).
void bound_walk_step(inout int i, inout bool waiting, inout int resume, inout WalkPass pass,
                     float tau, bool limit_size, bool shade, bool share, SurfacePoint p) {
    if (i == kEndOfWalk) return;
    if (waiting && i == resume) waiting = false;
    // One load of the node per step: llvmpipe gathers every field per lane,
    // and loads in different branches are not merged.
    GpuTreeNode node = tree_nodes[i];
    if (!waiting && left_out(node.flags)) {
        waiting = true;
        resume = node.escape;
    }
    bool refine = false;
    if (!waiting) {
        bool leaf = node.first_child == kNoChild;
        bool mixed = (node.flags & kNodeMixedTypes) != 0u;
        float key = 0.0;
        if (!leaf && !mixed)
            key = cluster_error_bound(node, p);
        refine = !leaf && (mixed || key > tau);
        // The lanes here all stand at node i (a lane that took an ancestor
        // as a cluster is waiting, and sits this vote out).
        if (kWalkShareCuts) {
            bool voted = subgroupAny(share && refine);
            if (share) refine = voted;
        }
        if (!refine) {
            waiting = true;
            if (limit_size && pass.size >= kWalkMaxCut) {
                pass.over = true;
                resume = kEndOfWalk;
            } else {
                if (shade) {
#ifdef LC_WALK_RECORDS
                    uint seen;
                    vec3 contribution = light_radiance_seen(cluster_light(i, node, p), p, seen);
                    record_cut_node(pass.size, uint(i), seen);
#else
                    vec3 contribution = light_radiance(cluster_light(i, node, p), p);
#endif
                    pass.radiance += contribution;
                    tally_indirect(pass.indirect, node.flags, leaf, contribution);
                }
                pass.size += 1u;
                pass.hash += cut_hash_term(uint(i));
                pass.worst = max(pass.worst, key);
                resume = node.escape;
            }
        }
    }
    i = subgroupAny(refine) ? node.first_child : node.escape;
}

// Where pass 0 starts: tau = +inf keeps the per-type roots.
GpuWalkState walk_start() {
    return GpuWalkState(vec3(0.0), 0u, 0u, uintBitsToFloat(0x7f800000u), 0.0, 0.0,
                        kWalkBisections << kWalkBisectionsShift, 0u, 0u, 0u, vec3(0.0), 0u,
                        vec3(0.0), 0.0, vec3(0.0), 0.0, vec3(0.0), 0.0, vec3(0.0), 0u,
                        vec3(0.0), 0.0, vec3(0.0), 0u, vec3(0.0), 0u);
}

// The cut at threshold tau (`shade` false: its size, hash and worst bound
// only). False when the walk or a ray of it was cut short.
bool walk_cut(float tau, bool limit_size, bool shade, bool share, out WalkPass pass, SurfacePoint p) {
    pass = WalkPass(vec3(0.0), 0u, 0u, 0.0, false, no_indirect_sums());
    int i = frame.node_count > 0u ? 0 : kEndOfWalk;  // an empty tree: an empty cut
    bool waiting = false;
    int resume = kEndOfWalk;
    g_shadow_walk_cut_short = false;
    // Two steps per iteration: the step is large, and more copies spill
    // (measured: 8 copies 1.4x slower).
    for (uint step = 0u; i != kEndOfWalk && step < frame.node_count; step += kWalkUnroll) {
        bound_walk_step(i, waiting, resume, pass, tau, limit_size, shade, share, p);
        bound_walk_step(i, waiting, resume, pass, tau, limit_size, shade, share, p);
    }
    return i == kEndOfWalk && !g_shadow_walk_cut_short;
}

// One pass of one lane's search (s.passes numbers it): walks with s.tau,
// then keeps the cut if it fit and sets the next threshold, or marks the
// search done. Returns false, leaving s as it was, when the device's loop
// limit (or a corrupt tree) ended the walk or one of its shadow rays early.
bool walk_pass(inout GpuWalkState s, SurfacePoint p) {
    bool limit_size = s.passes > 0u;
    bool bisecting = (s.flags & kWalkBisecting) != 0u;
    bool share = kWalkShareCuts && (s.flags & kWalkAlone) == 0u;
    WalkPass pass;
    // With shadow rays, a pass that may well exceed max-cut (bisecting, or
    // the last cut already a quarter of it) is sized first and shaded only
    // if it fits: the same decisions, without tracing the rays of cuts that
    // are thrown away. Sizing costs a walk of bounds; rays cost far more.
    bool size_first =
        kShadows && limit_size && (bisecting || s.size * 4u >= kWalkMaxCut);
    if (size_first && !walk_cut(s.tau, limit_size, false, share, pass, p)) return false;
    if (!(size_first && pass.over) && !walk_cut(s.tau, limit_size, true, share, pass, p)) return false;
    // A shaded pass that went over wrote records over the kept cut's.
    if (pass.over && !size_first) s.flags |= kWalkRecordsStale;
    if (share && pass.over) {
        // The same threshold again, on this lane's own walk (not counted as a pass).
        s.flags |= kWalkAlone;
        return true;
    }
    ++s.passes;
    if (s.passes >= kWalkMaxPasses) s.flags |= kWalkDone;  // unless the rule is met below
    if (pass.over) {
        s.flags |= kWalkBisecting;
        s.over_lo = s.tau;
    } else {
        s.flags &= ~kWalkRecordsStale;
        s.radiance = pass.radiance;
        if (kIndirectClamp) keep_indirect_sums(s, pass.indirect);
        s.size = pass.size;
        s.hash = pass.hash;
        float limit = kErrorRatio * max(max_channel(clamped_cut_total(pass.radiance, pass.indirect)), 0.0);
        if (!(pass.worst > limit)) {
            s.flags |= kWalkDone | kWalkRuleMet;
            return true;
        }
        s.fit_hi = pass.worst;
        if (!bisecting) {
            s.tau = next_walk_threshold(limit, pass.worst, kWalkMargin, kWalkShrink);
            return true;
        }
    }
    // Over max-cut once: bisect between the last fit and the last over.
    uint bisections_left = s.flags >> kWalkBisectionsShift;
    if (bisections_left == 0u) {
        s.flags |= kWalkDone;
        return true;
    }
    s.flags = (s.flags & ((1u << kWalkBisectionsShift) - 1u)) |
              ((bisections_left - 1u) << kWalkBisectionsShift);
    s.tau = bisection_threshold(s.fit_hi, s.over_lo);
    return true;
}

// The walk search over up to kWalkMaxPasses dispatches (Renderer::record;
// frame.walk_dispatch numbers them). Each dispatch runs passes until the pixel's
// search is done or llvmpipe's loop limit (lightcuts/device/limits.h) cuts a pass
// short; the search is then kept in walk_states and the cut-short pass runs
// again, whole, in the next dispatch with a fresh budget. Most pixels finish
// in the first dispatch, so the later ones are nearly empty. Only a pass that
// exceeds the limit on its own (the first of its dispatch) ends the search:
// the pixel keeps its last complete pass and counts in loop_limit_stops. A
// pixel is stored once, when its search ends; later dispatches skip it.
void bound_walk_dispatch(ivec2 pixel) {
    uint index = uint(pixel.y) * frame.width + uint(pixel.x);
    set_pixel_representatives(pixel);
    GpuWalkState s;
    if (frame.walk_dispatch == 0u) {
        s = walk_start();
    } else {
        s = walk_states[index];
        if ((s.flags & (kWalkDone | kWalkStorePending)) == kWalkDone) return;
    }
    SurfacePoint p;
    if (!load_surface(pixel, p)) {
        store_background(pixel);
        walk_states[index].flags = kWalkDone;
#ifdef LC_WALK_RECORDS
        finish_sample(vec3(0.0), 0u, false, kErrorRatio);
#endif
        return;
    }
    // Every dispatch completes a pass or ends the search, so kWalkMaxPasses
    // dispatches end every search; the last one stores whatever is left.
    bool last_dispatch = frame.walk_dispatch + 1u >= kWalkMaxPasses;
    bool limited = false;
    for (uint run = 0u; (s.flags & kWalkDone) == 0u; ++run) {
        if (!walk_pass(s, p)) {
            limited = true;
            if (run == 0u || last_dispatch) s.flags |= kWalkDone | kWalkLoopStop;
            break;
        }
    }
    if (last_dispatch) s.flags |= kWalkDone;
    g_shadow_walk_cut_short = false;  // in the flags: counted once, when the pixel is stored
    // Storing adds the classic lights, whose loop the spent budget would cut
    // short too: a search that ended where the limit fired is stored next time.
    if ((s.flags & kWalkDone) == 0u || (limited && !last_dispatch)) {
        if (limited && (s.flags & kWalkDone) != 0u) s.flags |= kWalkStorePending;
        walk_states[index] = s;
        flush_shadow_ray_count();
        return;
    }
    walk_states[index].flags = kWalkDone;
    bool loop_limit_stop = (s.flags & kWalkLoopStop) != 0u;
    // Stopped by max-cut, or still refining after the last pass.
    if ((s.flags & kWalkRuleMet) == 0u && !loop_limit_stop) atomicAdd(counters.max_cut_hits, 1u);
    vec3 radiance = clamp_indirect(pixel, s.radiance, indirect_sums_of(s));
#ifdef LC_WALK_RECORDS
    // Its records hold the kept cut: not cut short, not stale, under the cap.
    // A cut stopped by max-cut is shared too, with the ratio its largest
    // bound reached (the pixels between refine no finer than that).
    float total = max_channel(s.radiance);
    bool rule_met = (s.flags & kWalkRuleMet) != 0u;
    float reached_ratio = rule_met || !(total > 0.0) ? kErrorRatio : max(kErrorRatio, s.fit_hi / total);
    finish_sample(radiance, s.size, (s.flags & kWalkRecordsStale) == 0u && !loop_limit_stop, reached_ratio);
#endif
    store_pixel(pixel, radiance + classic_and_emitted_radiance(p), s.size, s.hash,
                loop_limit_stop);
}

#endif

#version 460
// The ReSTIR mode's first dispatch (Bitterli et al. 2020, Alg. 3 and 4): per
// pixel, kCandidates lights drawn from the light tree's root (the real-time
// mode's draw, stochastic_draw.glsl: intensity x a geometric estimate at the
// point; or by intensity alone, kRestirSourcePower), resampled by the target
// function (restir_target) into one reservoir; optionally its survivor's
// shadow ray (kCandidateVisibility); then the previous frame's reservoir of
// the same surface merged in (temporal reuse: reprojected, rejected on
// another surface, its M capped at 20 x kCandidates).
#extension GL_GOOGLE_include_directive : require

#include "restir_bindings.glsl"

const float kTemporalCap = 20.0;

// A draw from the tree's root (a root that is a leaf: that light, surely).
Descent root_descent() {
    g_pixel_key = cut_hash_term(g_restir_random);
    GpuTreeNode root = tree_nodes[0];
    int next = root.first_child == kNoChild ? ~int(root.representative) : 0;
    return Descent(next, 1.0, start_chain(restir_uniform()));
}

// One level of the power draw: the children weigh by intensity alone.
void draw_power_level(inout Descent d) {
    if (d.next < 0) return;
    GpuDrawPair pair = draw_pairs[d.next];
    float sum = pair.intensity0 + pair.intensity1;
    bool first = true;
    if (!(sum < 3.402823466e38)) {
        d.probability = 0.0;
    } else if (sum > 0.0) {
        first = chain_takes_first(d.chain, pair.intensity0, pair.intensity1);
        d.probability *= (first ? pair.intensity0 : pair.intensity1) / sum;
        if (chain_worn(d.chain)) d.chain = start_chain(restir_uniform());
    }
    d.next = first ? pair.child0 : pair.child1;
}

void descend_both_by_power(inout Descent a, inout Descent b) {
    for (uint level = 0u; (a.next >= 0 || b.next >= 0) && level < frame.node_count; level += 2u) {
        draw_power_level(a);
        draw_power_level(b);
        draw_power_level(a);
        draw_power_level(b);
    }
}

// A drawn candidate offered with weight p_hat / pdf; a draw the loop limit
// cut short, or of probability 0, counts and weighs nothing.
void offer_candidate(inout Reservoir r, Descent d, SurfacePoint p) {
    if (d.next >= 0 || !(d.probability > 0.0)) {
        if (d.next >= 0) g_shadow_walk_cut_short = true;
        reservoir_offer(r, 0u, 0.0, 1.0, 0.0);
        return;
    }
    uint light = uint(~d.next);
    float target = restir_target(leaf_lights[light], p);
    reservoir_offer(r, light, target / d.probability, 1.0, target);
}

// Resampled initial candidates, two descents at a time.
Reservoir initial_candidates(SurfacePoint p) {
    Reservoir r = empty_reservoir();
    if (frame.node_count == 0u) return r;
    for (uint k = 0u; k < kCandidates; k += 2u) {
        bool second = k + 1u < kCandidates;
        Descent a = root_descent();
        Descent b = root_descent();
        if (kSource == kRestirSourcePower)
            descend_both_by_power(a, b);
        else
            descend_both(a, b, p);
        offer_candidate(r, a, p);
        if (second) offer_candidate(r, b, p);
    }
    return r;
}

// The paper's visibility reuse: a survivor its shadow ray finds blocked
// keeps its M and loses its weight. In uniform control flow.
void test_candidate_visibility(inout Reservoir r, SurfacePoint p, bool surface) {
    if (!kCandidateVisibility) return;
    bool needed = surface && r.has_sample && r.target > 0.0;
    float v = light_visibility(held_light(r.light, needed), p.position, p.normal, needed);
    if (v == 0.0) r.has_sample = false;
}

// The previous frame's reservoir of this surface, or none (count 0).
GpuReservoir previous_reservoir(ivec2 pixel, SurfacePoint p) {
    GpuReservoir none = stored_reservoir(empty_reservoir(), 0.0, vec3(0.0), vec3(0.0));
    if (!kTemporal || temporal.history_valid == 0u) return none;
    ivec2 from = pixel;
    if (temporal.camera_moved != 0u && !previous_pixel(p.position, from)) return none;
    GpuReservoir prev = reservoirs_previous[reservoir_index(from)];
    if (!(prev.count > 0.0) || !similar_surfaces(p.position, p.normal, prev.position, prev.normal)) return none;
    prev.count = min(prev.count, kTemporalCap * float(kCandidates));
    return prev;
}

// Whether the previous reservoir could have produced `light` (its p_hat
// there, with this pixel's material; and its visibility there where its
// candidates were visibility-tested). In uniform control flow.
bool previous_could_produce(GpuReservoir prev, uint light, SurfacePoint p, bool needed) {
    SurfacePoint q = p;
    q.position = prev.position;
    q.normal = prev.normal;
    GpuLight l = held_light(light, needed);
    bool positive = needed && restir_target(l, q) > 0.0;
    if (kCandidateVisibility) positive = light_visibility(l, q.position, q.normal, positive) > 0.0 && positive;
    return positive;
}

// This frame's reservoir merged with the previous one, and its W.
Reservoir temporal_reuse(Reservoir r, ivec2 pixel, SurfacePoint p, bool surface, out float weight) {
    GpuReservoir prev = previous_reservoir(pixel, p);
    bool merge = surface && prev.count > 0.0;
    Reservoir s = empty_reservoir();
    // This frame's reservoir weighs its own w_sum: p_hat x W x M.
    reservoir_offer(s, r.light, r.has_sample ? r.weight_sum : 0.0, r.count, r.target);
    float prev_target = merge && prev.weight > 0.0 ? restir_target(leaf_lights[prev.light], p) : 0.0;
    if (merge) reservoir_offer(s, prev.light, prev_target * prev.weight * prev.count, prev.count, prev_target);
    float normaliser = s.count;
    if (kUnbiased) {
        // 1/Z: only the reservoirs whose candidates could be y count.
        bool counted = previous_could_produce(prev, s.light, p, merge && s.has_sample);
        normaliser = r.count + (counted ? prev.count : 0.0);
    }
    weight = contribution_weight(s, normaliser);
    return s;
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = pixel.x < int(frame.width) && pixel.y < int(frame.height);
    SurfacePoint p;
    // Lanes off the image walk the shared shadow rays for pixel (0, 0) and store nothing.
    bool surface = load_surface(inside ? pixel : ivec2(0), p) && inside;
    seed_restir_random(pixel, frame.frame_seed, 0u);
    Reservoir r = surface ? initial_candidates(p) : empty_reservoir();
    test_candidate_visibility(r, p, surface);
    float weight = 0.0;
    Reservoir s = temporal_reuse(r, pixel, p, surface, weight);
    flush_pixel_counters(false);
    if (!inside) return;
    reservoirs_temporal[reservoir_index(pixel)] =
        stored_reservoir(s, surface ? weight : 0.0, surface ? p.position : vec3(0.0), p.normal);
}

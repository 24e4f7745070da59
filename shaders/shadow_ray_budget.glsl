// The real-time mode's fixed shadow-ray budget (realtime_lighting.comp,
// render --realtime-rays S): every drawn light of the block's cut is shaded
// without its visibility, S of them are picked, each in proportion to that
// unshadowed radiance (one weighted reservoir per pick, filled as the cut is
// walked, its uniforms spread over the picks and the frames), and only the
// picks trace a shadow ray. A pick j estimates the
// cut's visible radiance as c_j V_j / P(j) = V_j W c_j / w_j (w = the largest
// channel of c, W their sum over the cut); the mean of S picks is unbiased,
// and its noise comes from visibility alone: none where the cut's lights are
// all seen alike. Unreal's MegaLights and RTXDI spend their rays this way.
#ifndef LC_SHADOW_RAY_BUDGET_GLSL
#define LC_SHADOW_RAY_BUDGET_GLSL

#include "frame_strata.glsl"
#include "indirect_clamp.glsl"
#include "pixel_representative.glsl"

layout(constant_id = kSpecStochasticRays) const uint kStochasticRays = 0u;

struct BudgetPick {
    uint light;     // the leaf light (leaf_lights) the shadow ray aims at
    vec3 radiance;  // its unshadowed radiance c at the pixel
    float weight;   // w: c's largest channel; 0 for no pick
    uint node_flags;
    bool leaf;
};

struct ShadowBudget {
    BudgetPick picks[kMaxStochasticRays];
    StratifiedChain chains[kMaxStochasticRays];  // each pick's uniform
    float total;  // W: the sum of w over the cut so far
};

// The budget applies when it is smaller than the cut (uniform over the
// workgroup, which shares the cut) and no VPL leaf is clamped: the clamp
// reads each leaf's own shadowed contribution, which a pick does not give.
bool shadow_budget_applies(uint cut_size) {
    return kStochasticRays > 0u && kStochasticRays < cut_size && !kIndirectClamp;
}

// The picks' uniforms are one stratum of the frame spread over the S picks
// (u + s / S: systematic, so a light worth several picks gets about that
// many) and stretched as the cut is walked (frame_strata.glsl).
ShadowBudget empty_shadow_budget() {
    ShadowBudget b;
    float u = frame_stratum(kStrataPick, 0u);
    for (uint s = 0u; s < kMaxStochasticRays; ++s) {
        b.picks[s] = BudgetPick(0u, vec3(0.0), 0.0, 0u, false);
        b.chains[s] = start_chain(fract(u + float(s) / float(max(kStochasticRays, 1u))));
    }
    b.total = 0.0;
    return b;
}

// A fresh uniform for pick s at the cut's k-th node, this frame's own: the
// pixel's draws key mixed with the pick, so picks and descents are independent.
float fresh_pick_uniform(uint s, uint k) {
    return representative_uniform(cut_hash_term(g_pixel_key + 0x68E31DA4u * (s + 1u)), k);
}

// Offers the cut's k-th drawn light to every pick: pick s takes it with
// probability w / W so far (its uniform in the lower share), which leaves
// each light picked with w / W in the end.
void offer_to_budget(inout ShadowBudget b, uint k, uint light, vec3 radiance, uint node_flags, bool leaf) {
    float w = max(radiance.x, max(radiance.y, radiance.z));
    if (!(w > 0.0)) return;
    float before = b.total;
    b.total += w;
    for (uint s = 0u; s < kStochasticRays; ++s) {
        if (chain_takes_first(b.chains[s], w, before)) b.picks[s] = BudgetPick(light, radiance, w, node_flags, leaf);
        if (chain_worn(b.chains[s])) b.chains[s] = start_chain(fresh_pick_uniform(s, k));
    }
}

// The picks' shadow rays and their estimate of the cut's visible radiance,
// added to `cut`. In uniform control flow: the shadow walk is the subgroup's.
void resolve_shadow_budget(ShadowBudget b, SurfacePoint p, inout Cut cut) {
    for (uint s = 0u; s < kStochasticRays; ++s) {
        BudgetPick pick = b.picks[s];
        bool needed = pick.weight > 0.0;
        float v = kShadows ? light_visibility(leaf_lights[pick.light], p.position, p.normal, needed) : 1.0;
        float scale = needed ? v * (b.total / (pick.weight * float(kStochasticRays))) : 0.0;
        vec3 estimate = pick.radiance * scale;
        cut.radiance += estimate;
        tally_indirect(cut.indirect, pick.node_flags, pick.leaf, estimate);
    }
}

#endif

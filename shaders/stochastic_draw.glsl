// The real-time mode's light draw (realtime_lighting.comp): from a cut node
// down to one leaf light, each child taken with probability in proportion to
// its intensity x an estimate of cos / d^2 at the point
// (stochastic_sphere_geometry, pixel_representative.glsl.h), one uniform
// stretched down the levels and spread over frames (frame_strata.glsl). One GpuDrawPair
// record per level (set kDrawPairSet, lightcuts/tree/draw_pairs.h): the
// children's spheres, intensities and destinations in 48 bytes, where the
// tree's nodes would take three dependent loads of 64 bytes.
#ifndef LC_STOCHASTIC_DRAW_GLSL
#define LC_STOCHASTIC_DRAW_GLSL

#include "frame_strata.glsl"
#include "pixel_representative.glsl"

layout(std430, set = kDrawPairSet, binding = kBindDrawPairs) readonly buffer DrawPairs {
    GpuDrawPair draw_pairs[];
};

float child_draw_weight(vec3 centre, float radius, float intensity, vec3 x, vec3 n) {
    return radius < 0.0 ? intensity : intensity * stochastic_sphere_geometry(centre - x, radius, n);
}

// A draw under way: the node it is at (~light once at a leaf), the
// probability of the path so far, and its uniform (frame_strata.glsl).
struct Descent {
    int next;
    float probability;
    StratifiedChain chain;
};

// One level: from internal node d.next to the child the pixel's draw takes
// (a node index, or ~light for a leaf), the probability multiplied by the
// child's. A zero total keeps the first child (nothing to weigh); a
// non-finite one draws nothing (probability 0). A leaf reached stays.
void draw_one_level(inout Descent d, SurfacePoint p) {
    if (d.next < 0) return;
    GpuDrawPair pair = draw_pairs[d.next];
    float w0 = child_draw_weight(pair.centre0, pair.radius0, pair.intensity0, p.position, p.normal);
    float w1 = child_draw_weight(pair.centre1, pair.radius1, pair.intensity1, p.position, p.normal);
    float sum = w0 + w1;
    bool first = true;
    if (!(sum < 3.402823466e38)) {
        d.probability = 0.0;
    } else if (sum > 0.0) {
        first = chain_takes_first(d.chain, w0, w1);
        d.probability *= (first ? w0 : w1) / sum;
        if (chain_worn(d.chain)) d.chain = start_chain(representative_uniform(g_pixel_key, uint(d.next)));
    }
    d.next = first ? pair.child0 : pair.child1;
}

// Cut node i's draw, its uniform the frame's stratum for the node.
Descent start_descent(int i, GpuTreeNode node) {
    int next = node.first_child == kNoChild ? ~int(node.representative) : i;
    return Descent(next, 1.0, start_chain(frame_stratum(kStrataDraw, uint(i))));
}

// The light cut node `node` is evaluated through at p: the leaf light its
// descent reached, its intensity over its probability (a leaf node keeps its
// own). A descent the device's loop limit cut short keeps the node's stored
// representative with the cluster's intensity, and is counted like a
// cut-short shadow walk.
GpuLight finish_descent(Descent d, GpuTreeNode node) {
    if (node.first_child == kNoChild || d.next >= 0) {
        if (d.next >= 0) g_shadow_walk_cut_short = true;
        GpuLight kept = leaf_lights[node.representative];
        kept.intensity = node.intensity;
        return kept;
    }
    GpuLight light = leaf_lights[uint(~d.next)];
    light.intensity = d.probability > 0.0 ? light.intensity / d.probability : vec3(0.0);
    return light;
}

// The leaf light finish_descent evaluates the node through (its position is
// where a shadow ray aims).
uint drawn_light_index(Descent d, GpuTreeNode node) {
    return node.first_child == kNoChild || d.next >= 0 ? node.representative : uint(~d.next);
}

// Two descents side by side: they are independent, so each level's loads of
// one overlap the other's (alone, a GPU lane waits on every level's load).
// Two levels of each per iteration: each back edge spends llvmpipe's loop budget.
void descend_both(inout Descent a, inout Descent b, SurfacePoint p) {
    for (uint level = 0u; (a.next >= 0 || b.next >= 0) && level < frame.node_count; level += 2u) {
        draw_one_level(a, p);
        draw_one_level(b, p);
        draw_one_level(a, p);
        draw_one_level(b, p);
    }
}

#endif

// Per-pixel representatives for the bound criterion's passes
// (lightcuts/device/pixel_representative.glsl.h): a cluster is evaluated
// through the leaf this pixel's draw reaches from it, a descent of the
// cluster's subtree, in proportion to intensity (kRepresentativesPixel) or
// to intensity x a geometric bound at the point (kRepresentativesImportance). Mirrors
// pixel_draw() in cpu_evaluator.cpp. The bounds keep reading the node's own
// representative (its range window).
#ifndef LC_PIXEL_REPRESENTATIVE_GLSL
#define LC_PIXEL_REPRESENTATIVE_GLSL

#include "frame_bindings.glsl"
#include "lightcuts/device/pixel_representative.glsl.h"
#include "material_model.glsl"
#include "shadow_rays.glsl"

layout(constant_id = kSpecRepresentatives) const uint kRepresentatives = kRepresentativesTree;
layout(constant_id = kSpecRepresentativeSeed) const uint kRepresentativeSeed = 0u;

// This invocation's pixel key (set_pixel_representatives).
uint g_pixel_key = 0u;

void set_pixel_representatives(ivec2 pixel) {
    if (kRepresentatives != kRepresentativesTree)
        g_pixel_key = pixel_representative_key(uint(pixel.x), uint(pixel.y), kRepresentativeSeed);
}

// A leaf drawn for the pixel and the probability it was drawn with (1 for
// the tree's representative and for kRepresentativesPixel, whose estimate
// keeps the cluster's intensity).
struct PixelDraw {
    uint light;  // index into leaf_lights
    float probability;
};

// Draws whose probabilities divide the estimate (the leaf's own intensity
// over its probability): by importance. (The real-time mode draws through
// its own records, stochastic_draw.glsl.)
bool draws_by_weight() { return kRepresentatives == kRepresentativesImportance; }

// A child's weight in the draw.
float draw_weight(int i, SurfacePoint p) {
    if (!draws_by_weight()) return representative_scalar(tree_nodes[i].intensity);
    // A junction of several light types has a box of positions and directions
    // mixed: it weighs by intensity alone, so the draw stays unbiased (the cut
    // searches always refine one, so no draw starts above it).
    uint flags = tree_nodes[i].flags;
    if ((flags & kNodeMixedTypes) != 0u) return representative_scalar(tree_nodes[i].intensity);
    bool directional = (flags >> kNodeTypeShift) == kLightDirectional;
    return importance_weight(tree_nodes[i].intensity,
                             importance_geometry(tree_nodes[i].bbox_min, tree_nodes[i].bbox_max,
                                                 p.position, p.normal, directional));
}

// One level of the descent: from node i (whose first child and escape are
// given) to the child this pixel's draw takes. Only the fields read are
// loaded: llvmpipe gathers a whole struct per lane.
void descend_one_level(inout int i, inout int first_child, inout int escape, inout float probability,
                       SurfacePoint p) {
    if (first_child == kNoChild) return;
    int c0 = first_child;
    int c1 = tree_nodes[c0].escape;
    bool take_first = true;
    if (c1 != kEndOfWalk && c1 != escape) {
        float w0 = draw_weight(c0, p);
        float w1 = draw_weight(c1, p);
        take_first = pixel_takes_first(g_pixel_key, uint(i), w0, w1);
        if (draws_by_weight() && w0 + w1 > 0.0)
            probability *= (take_first ? w0 : w1) / (w0 + w1);
    }
    i = take_first ? c0 : c1;
    first_child = tree_nodes[i].first_child;
    // The first child's subtree ends where its sibling starts; the last
    // child's where its parent's does.
    if (take_first) escape = c1;
}

// The leaf light node i is evaluated through at this pixel: its stored
// representative, or this pixel's draw. A descent the device's loop limit
// cuts short keeps the stored one and is noted like a cut-short walk (the
// walk search runs the pass again).
PixelDraw pixel_draw(int i, GpuTreeNode node, SurfacePoint p) {
    if (kRepresentatives == kRepresentativesTree || node.first_child == kNoChild)
        return PixelDraw(node.representative, 1.0);
    int first_child = node.first_child;
    int escape = node.escape;
    float probability = 1.0;
    // Two levels per iteration: each back edge spends llvmpipe's loop budget.
    for (uint level = 0u; first_child != kNoChild && level < frame.node_count; level += 2u) {
        descend_one_level(i, first_child, escape, probability, p);
        descend_one_level(i, first_child, escape, probability, p);
    }
    if (first_child != kNoChild) {
        g_shadow_walk_cut_short = true;
        return PixelDraw(node.representative, 1.0);
    }
    return PixelDraw(tree_nodes[i].representative, probability);
}

// Node i evaluated as a cluster: the drawn leaf light with the cluster's
// intensity, or with its own over its probability (kRepresentativesImportance:
// the leaf light's colour, unbiased per channel).
GpuLight cluster_light(int i, GpuTreeNode node, SurfacePoint p) {
    PixelDraw draw = pixel_draw(i, node, p);
    GpuLight light = leaf_lights[draw.light];
    if (draws_by_weight() && node.first_child != kNoChild)
        light.intensity = draw.probability > 0.0 ? light.intensity / draw.probability : vec3(0.0);
    else
        light.intensity = node.intensity;
    return light;
}

#endif

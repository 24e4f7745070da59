// Per-pixel representatives for the bound criterion's passes
// (lightcuts/device/pixel_representative.glsl.h): a cluster is evaluated
// through the leaf this pixel's draw reaches from it, a descent of the
// cluster's subtree. Mirrors pixel_representative() in cpu_evaluator.cpp.
// The bounds keep reading the node's own representative (its range window).
#ifndef LC_PIXEL_REPRESENTATIVE_GLSL
#define LC_PIXEL_REPRESENTATIVE_GLSL

#include "frame_bindings.glsl"
#include "lightcuts/device/pixel_representative.glsl.h"
#include "shadow_rays.glsl"

layout(constant_id = kSpecPixelRepresentatives) const bool kPixelRepresentatives = false;
layout(constant_id = kSpecRepresentativeSeed) const uint kRepresentativeSeed = 0u;

// This invocation's pixel key (set_pixel_representatives).
uint g_pixel_key = 0u;

void set_pixel_representatives(ivec2 pixel) {
    if (kPixelRepresentatives)
        g_pixel_key = pixel_representative_key(uint(pixel.x), uint(pixel.y), kRepresentativeSeed);
}

// One level of the descent: from node i (whose first child and escape are
// given) to the child this pixel's draw takes. Only the fields read are
// loaded: llvmpipe gathers a whole struct per lane.
void descend_one_level(inout int i, inout int first_child, inout int escape) {
    if (first_child == kEndOfWalk) return;
    int c0 = first_child;
    int c1 = tree_nodes[c0].escape;
    bool take_first = c1 == kEndOfWalk || c1 == escape ||
                      pixel_takes_first_child(g_pixel_key, uint(i), tree_nodes[c0].intensity,
                                              tree_nodes[c1].intensity);
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
uint pixel_representative(int i, GpuTreeNode node) {
    if (!kPixelRepresentatives || node.first_child == kEndOfWalk) return node.representative;
    int first_child = node.first_child;
    int escape = node.escape;
    // Two levels per iteration: each back edge spends llvmpipe's loop budget.
    for (uint level = 0u; first_child != kEndOfWalk && level < frame.node_count; level += 2u) {
        descend_one_level(i, first_child, escape);
        descend_one_level(i, first_child, escape);
    }
    if (first_child != kEndOfWalk) {
        g_shadow_walk_cut_short = true;
        return node.representative;
    }
    return tree_nodes[i].representative;
}

#endif

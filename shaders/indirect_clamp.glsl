// Indirect light in the lighting passes: the automatic clamp of its leaves
// (lightcuts/device/indirect_clamp.glsl.h, mirrored by cpu_evaluator.cpp) and
// render --indirect off, which leaves every indirect node out. Both constants
// are false for a tree without indirect lights, which then shades as before.
#ifndef LC_INDIRECT_CLAMP_GLSL
#define LC_INDIRECT_CLAMP_GLSL

#include "frame_bindings.glsl"
#include "lightcuts/device/indirect_clamp.glsl.h"

layout(constant_id = kSpecIndirectClamp) const bool kIndirectClamp = false;
layout(constant_id = kSpecIndirectOff) const bool kIndirectOff = false;
// The bound criterion's error ratio; the clamp's ratio is half of it.
layout(constant_id = kSpecErrorRatio) const float kErrorRatio = 0.02;

bool left_out(uint node_flags) { return kIndirectOff && (node_flags & kNodeIndirect) != 0u; }

// Whether a tree node that is a leaf goes to the clamp: a VPL, not a patch.
bool clamped_node(uint node_flags, bool leaf) {
    return clamped_leaf((node_flags & kNodeIndirect) != 0u, (node_flags & kNodePatch) != 0u, leaf);
}

// One cut node's contribution, kept for the clamp.
void tally_indirect(inout IndirectSums s, uint node_flags, bool leaf, vec3 contribution) {
    if (kIndirectClamp) add_cut_node(s, (node_flags & kNodeIndirect) != 0u, clamped_node(node_flags, leaf), contribution);
}

// The cut's total as the stopping rule reads it: clamped.
vec3 clamped_cut_total(vec3 total, IndirectSums s) {
    if (!kIndirectClamp || s.leaves == 0u) return total;
    vec3 removed;
    return indirect_clamped(total, s, 0.5 * kErrorRatio, removed);
}

// The same for the heap, whose sums hold only its indirect leaves.
vec3 clamped_heap_total(vec3 total, IndirectSums leaves) {
    if (!kIndirectClamp || leaves.leaves == 0u) return total;
    return clamped_running_total(total, leaves, 0.5 * kErrorRatio);
}

// The cut's radiance with its indirect leaves clamped. The pixel's indirect
// light and what the clamp removed stay in walk_states for the render stats.
vec3 clamp_indirect(ivec2 pixel, vec3 cut_radiance, IndirectSums s) {
    if (!kIndirectClamp) return cut_radiance;
    vec3 removed = vec3(0.0);
    vec3 clamped = cut_radiance;
    if (s.leaves > 0u) clamped = indirect_clamped(cut_radiance, s, 0.5 * kErrorRatio, removed);
    uint index = uint(pixel.y) * frame.width + uint(pixel.x);
    vec3 indirect = s.largest + s.second + s.rest + s.clusters;
    walk_states[index].indirect_energy = indirect.x + indirect.y + indirect.z;
    walk_states[index].clamped_energy = removed.x + removed.y + removed.z;
    return clamped;
}

// The sums kept in a pixel's GpuWalkState between dispatches.
IndirectSums indirect_sums_of(GpuWalkState state) {
    return IndirectSums(state.indirect_largest, state.indirect_second, state.indirect_rest,
                        state.indirect_rest_max, state.indirect_others, state.indirect_clusters,
                        state.indirect_leaves);
}

void keep_indirect_sums(inout GpuWalkState state, IndirectSums s) {
    state.indirect_largest = s.largest;
    state.indirect_second = s.second;
    state.indirect_rest = s.rest;
    state.indirect_rest_max = s.rest_max;
    state.indirect_others = s.others;
    state.indirect_clusters = s.clusters;
    state.indirect_leaves = s.leaves;
}

// Reference mode's exact clamp (indirect_clamp.glsl.h): whether this frame
// runs Newton's passes after the sums.
bool exact_clamp() { return kIndirectClamp && frame.clamp_passes > 0u; }

// The sums' end: the pixel's unclamped radiance, its sums and Newton's start,
// kept in walk_states[index] for the passes.
void begin_exact_clamp(uint index, vec3 radiance, IndirectSums s) {
    GpuWalkState state = walk_states[index];
    keep_indirect_sums(state, s);
    state.radiance = radiance;
    for (int c = 0; c < 3; ++c)
        state.clamp_threshold[c] = exact_clamp_start(s.others[c], s.largest[c], s.second[c], s.rest[c],
                                                     0.5 * kErrorRatio);
    walk_states[index] = state;
}

// A pass's end, from its tally at the pixel's threshold: Newton's step; after
// the last pass, the clamped radiance (the classic lights and emission not
// included) with the statistics clamp_indirect() keeps, and the step's
// largest relative change.
bool end_exact_clamp_pass(uint index, vec3 below, vec3 above, out vec3 clamped) {
    GpuWalkState state = walk_states[index];
    IndirectSums s = indirect_sums_of(state);
    vec3 t = state.clamp_threshold;
    vec3 next;
    for (int c = 0; c < 3; ++c) next[c] = exact_clamp_step(s.others[c], below[c], above[c], t[c], 0.5 * kErrorRatio);
    clamped = state.radiance;
    if (frame.clamp_pass < frame.clamp_passes) {
        walk_states[index].clamp_threshold = next;
        return false;
    }
    vec3 leaves = s.largest + s.second + s.rest;
    vec3 removed = vec3(0.0);
    float change = 0.0;
    for (int c = 0; c < 3; ++c) {
        if (t[c] > 0.0) change = max(change, (t[c] - next[c]) / t[c]);
        // A channel the clamp leaves alone is exactly its total.
        if (above[c] == 0.0) continue;
        float kept = below[c] + above[c] * next[c];
        clamped[c] = s.others[c] + kept;
        removed[c] = max(leaves[c] - kept, 0.0);
    }
    vec3 indirect = leaves + s.clusters;
    walk_states[index].indirect_energy = indirect.x + indirect.y + indirect.z;
    walk_states[index].clamped_energy = removed.x + removed.y + removed.z;
    walk_states[index].clamp_threshold = next;
    walk_states[index].clamp_change = change;
    return true;
}

void store_indirect_sums(uint index, IndirectSums s) {
    GpuWalkState state = walk_states[index];
    keep_indirect_sums(state, s);
    walk_states[index] = state;
}

#endif

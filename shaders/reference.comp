#version 460
// Reference mode: every tree leaf (or scene light) plus every classic light,
// summed exactly in float at each pixel with geometry, each light with its
// shadow ray when the scene has shadows. One dispatch sums the leaves
// [light_begin, light_end) onto the previous dispatches' partial sum, so that
// no invocation exceeds llvmpipe's loop budget (Renderer::reference_chunk):
// the first dispatch adds the classic lights and emission, the last one
// stores the pixel with its checks and counters.
//
// A small image (reference_pass.cpp) splits each dispatch's leaves over the
// dispatch's layers of workgroups (gl_NumWorkGroups.z parts): an 8x8 image is
// one workgroup, which would leave all but one of the device's threads idle.
// Part z of a pixel adds its leaves to its own sum, kept in the walk search's
// per-pixel scratch (walk_states[z * pixels + pixel].radiance; no walk runs in
// a reference frame), and a last dispatch with no leaves (light_begin ==
// light_end) adds the parts in order and stores the pixel.
//
// A tree with indirect lights (indirect_clamp.glsl) clamps them like the
// lightcuts passes, so that their error is measured against a clamped
// reference: every indirect leaf is tallied (the sums kept beside the partial
// sum), and the classic lights and emission join only after the clamp, in
// the dispatch that stores the pixel. --indirect off leaves them out.
//
// The reference clamps its VPLs exactly (indirect_clamp.glsl.h), where a cut
// approximates the clamp from its two largest leaves: after the pass that
// sums the leaves (frame.clamp_pass 0), frame.clamp_passes more passes over
// them (same dispatches, same parts) tally the VPLs at the pixel's threshold
// and take Newton's step; the last one stores the pixel. Those passes shade
// the VPLs only: the rest of the pixel is known from the sums. Where the
// frame keeps visibility (frame.vpl_visibility_stride > 0), the sums' pass
// records which VPLs' shadow rays were blocked and Newton's passes read the
// bits instead of tracing each ray again: the same values, one ray per VPL.
#extension GL_GOOGLE_include_directive : require

#include "lighting_pass.glsl"

layout(local_size_x_id = kSpecWorkgroupX, local_size_y_id = kSpecWorkgroupY) in;

// This invocation's pixel, row-major (the kept visibility's index).
uint g_pixel_index = 0u;

bool keeps_vpl_visibility() { return kShadows && frame.vpl_visibility_stride > 0u; }

// Where leaf i's bit is: the GpuVisibilityBits word and the bit in it.
uvec2 visibility_bit(uint i) {
    return uvec2(g_pixel_index * frame.vpl_visibility_stride + (i >> 7u), i & 127u);
}

// A VPL's radiance with its shadow ray, the ray's answer kept for Newton's
// passes; light_radiance's arithmetic, so the sums are the same bits.
vec3 vpl_radiance_keeping_visibility(uint i, SurfacePoint p) {
    GpuLight light = leaf_lights[i];
    vec3 l;
    vec3 e = light_irradiance(light, p.position, p.normal, l);
    float v = light_visibility(light, p.position, p.normal, max(e.x, max(e.y, e.z)) > 0.0);
    if (v == 0.0) {
        uvec2 bit = visibility_bit(i);
        atomicOr(vpl_visibility[bit.x].words[bit.y >> 5u], 1u << (bit.y & 31u));
    }
    e *= v;
    return brdf_toward(p, l) * e;
}

// The same VPL in Newton's passes: its kept visibility, no ray.
vec3 vpl_radiance_from_kept_visibility(uint i, SurfacePoint p) {
    GpuLight light = leaf_lights[i];
    vec3 l;
    vec3 e = light_irradiance(light, p.position, p.normal, l);
    uvec2 bit = visibility_bit(i);
    bool blocked = (vpl_visibility[bit.x].words[bit.y >> 5u] & (1u << (bit.y & 31u))) != 0u;
    e *= blocked ? 0.0 : 1.0;
    return brdf_toward(p, l) * e;
}

vec3 leaves_radiance(uint begin, uint end, SurfacePoint p) {
    vec3 radiance = vec3(0.0);
    uint i = begin;
    for (; i + kLoopUnroll <= end; i += kLoopUnroll) {
        radiance += light_radiance(leaf_lights[i], p);
        radiance += light_radiance(leaf_lights[i + 1u], p);
        radiance += light_radiance(leaf_lights[i + 2u], p);
        radiance += light_radiance(leaf_lights[i + 3u], p);
    }
    for (; i < end; ++i) radiance += light_radiance(leaf_lights[i], p);
    return radiance;
}

// One leaf of a tree with indirect lights: tallied for the clamp, or left out.
void add_leaf(inout vec3 radiance, inout IndirectSums s, uint i, SurfacePoint p) {
    bool indirect = (leaf_lights[i].flags & kGpuLightIndirect) != 0u;
    if (kIndirectOff && indirect) return;
    bool is_patch = (leaf_lights[i].flags & kGpuLightPatch) != 0u;
    // The VPLs Newton's passes tally again (tally_exact_leaf).
    bool kept = indirect && !is_patch && exact_clamp() && keeps_vpl_visibility();
    vec3 contribution = kept ? vpl_radiance_keeping_visibility(i, p) : light_radiance(leaf_lights[i], p);
    radiance += contribution;
    if (kIndirectClamp) add_cut_node(s, indirect, clamped_leaf(indirect, is_patch, true), contribution);
}

vec3 leaves_radiance_tallied(uint begin, uint end, inout IndirectSums s, SurfacePoint p) {
    vec3 radiance = vec3(0.0);
    uint i = begin;
    for (; i + kLoopUnroll <= end; i += kLoopUnroll) {
        add_leaf(radiance, s, i, p);
        add_leaf(radiance, s, i + 1u, p);
        add_leaf(radiance, s, i + 2u, p);
        add_leaf(radiance, s, i + 3u, p);
    }
    for (; i < end; ++i) add_leaf(radiance, s, i, p);
    return radiance;
}

// A tree with indirect lights: the leaves [begin, end) onto `previous`, the
// part's partial sum, whose indirect sums walk_states[at] keeps.
vec3 indirect_leaves_onto(vec3 previous, uint at, bool first, uint begin, uint end,
                          out IndirectSums s, SurfacePoint p) {
    s = first ? no_indirect_sums() : indirect_sums_of(walk_states[at]);
    vec3 radiance = previous + leaves_radiance_tallied(begin, end, s, p);
    if (kIndirectClamp) store_indirect_sums(at, s);
    return radiance;
}

// This part's share [begin, end) of the dispatch's leaves (layer
// gl_WorkGroupID.z of `parts`), for the sums and Newton's passes alike.
void part_leaves(uint parts, out uint begin, out uint end) {
    const uint part = (frame.light_end - frame.light_begin + parts - 1u) / parts;
    begin = min(frame.light_begin + gl_WorkGroupID.z * part, frame.light_end);
    end = min(begin + part, frame.light_end);
}

// Newton's passes: one VPL at the pixel's threshold t.
void tally_exact_leaf(uint i, vec3 t, inout vec3 below, inout vec3 above, SurfacePoint p) {
    if ((leaf_lights[i].flags & (kGpuLightIndirect | kGpuLightPatch)) != kGpuLightIndirect) return;
    vec3 contribution = keeps_vpl_visibility() ? vpl_radiance_from_kept_visibility(i, p)
                                               : light_radiance(leaf_lights[i], p);
    tally_exact_clamp(below, above, contribution, t);
}

void tally_exact_leaves(uint begin, uint end, vec3 t, inout vec3 below, inout vec3 above, SurfacePoint p) {
    uint i = begin;
    for (; i + kLoopUnroll <= end; i += kLoopUnroll) {
        tally_exact_leaf(i, t, below, above, p);
        tally_exact_leaf(i + 1u, t, below, above, p);
        tally_exact_leaf(i + 2u, t, below, above, p);
        tally_exact_leaf(i + 3u, t, below, above, p);
    }
    for (; i < end; ++i) tally_exact_leaf(i, t, below, above, p);
}

// A pass's tally of the whole pixel: Newton's step, and the pixel after the last pass.
void finish_exact_clamp_pass(ivec2 pixel, uint index, vec3 below, vec3 above, SurfacePoint p) {
    vec3 clamped;
    if (end_exact_clamp_pass(index, below, above, clamped)) {
        store_pixel(pixel, clamped + classic_and_emitted_radiance(p), frame.leaf_count, 0u, false);
    } else {
        flush_pixel_counters(false);
    }
}

// One dispatch of Newton's pass frame.clamp_pass, split like the sums: each
// part tallies its leaves in its own walk state, at the threshold its pixel
// keeps in the first part's state.
void exact_clamp_pass(ivec2 pixel, SurfacePoint p) {
    const uint parts = gl_NumWorkGroups.z;
    const uint pixels = frame.width * frame.height;
    const uint index = uint(pixel.y) * frame.width + uint(pixel.x);
    if (parts > 1u && frame.light_begin == frame.light_end) {
        if (gl_WorkGroupID.z != 0u) return;
        vec3 below = vec3(0.0);
        vec3 above = vec3(0.0);
        for (uint z = 0u; z < parts; ++z) {
            below += walk_states[z * pixels + index].clamp_below;
            above += walk_states[z * pixels + index].clamp_above;
        }
        finish_exact_clamp_pass(pixel, index, below, above, p);
        return;
    }
    uint begin = frame.light_begin;
    uint end = min(frame.light_end, frame.leaf_count);
    uint at = index;
    if (parts > 1u) {
        part_leaves(parts, begin, end);
        at = gl_WorkGroupID.z * pixels + index;
    }
    const bool first = frame.light_begin == 0u;
    vec3 below = first ? vec3(0.0) : walk_states[at].clamp_below;
    vec3 above = first ? vec3(0.0) : walk_states[at].clamp_above;
    tally_exact_leaves(begin, end, walk_states[index].clamp_threshold, below, above, p);
    if (parts == 1u && frame.light_end >= frame.leaf_count) {
        finish_exact_clamp_pass(pixel, index, below, above, p);
        return;
    }
    walk_states[at].clamp_below = below;
    walk_states[at].clamp_above = above;
    flush_pixel_counters(false);
}

// One part: the dispatch's leaves onto the pixel's sum in the HDR image.
void sum_onto_the_image(ivec2 pixel, SurfacePoint p) {
    const bool first = frame.light_begin == 0u;
    const bool last = frame.light_end >= frame.leaf_count;
    const uint end = min(frame.light_end, frame.leaf_count);
    vec3 radiance;
    if (kIndirectClamp || kIndirectOff) {
        const uint index = uint(pixel.y) * frame.width + uint(pixel.x);
        const vec3 previous = first ? vec3(0.0) : imageLoad(hdr_image, pixel).rgb;
        IndirectSums s;
        radiance = indirect_leaves_onto(previous, index, first, frame.light_begin, end, s, p);
        if (last && exact_clamp()) {
            begin_exact_clamp(index, radiance, s);
            flush_pixel_counters(false);
            return;
        }
        if (last) radiance = clamp_indirect(pixel, radiance, s) + classic_and_emitted_radiance(p);
    } else {
        radiance = leaves_radiance(frame.light_begin, end, p);
        radiance += first ? classic_and_emitted_radiance(p) : imageLoad(hdr_image, pixel).rgb;
    }
    if (last) {
        // Every leaf is in the "cut"; the hash is not needed for reference pixels.
        store_pixel(pixel, radiance, frame.leaf_count, 0u, false);
    } else {
        imageStore(hdr_image, pixel, vec4(radiance, 1.0));
        flush_pixel_counters(false);
    }
}

// This invocation's pixel: its global id, or its place on the lattice of tiles.
ivec2 dispatched_pixel() {
    if (frame.lattice_step == 0u) return ivec2(gl_GlobalInvocationID.xy);
    uvec2 group = gl_WorkGroupID.xy * frame.lattice_step + uvec2(frame.lattice_origin_x, frame.lattice_origin_y);
    return ivec2(group * gl_WorkGroupSize.xy + gl_LocalInvocationID.xy);
}

void main() {
    ivec2 pixel = dispatched_pixel();
    if (pixel.x >= int(frame.width) || pixel.y >= int(frame.height)) return;
    SurfacePoint p;
    if (!load_surface(pixel, p)) {
        store_background(pixel);
        return;
    }
    g_pixel_index = uint(pixel.y) * frame.width + uint(pixel.x);
    if (frame.clamp_pass > 0u) {
        exact_clamp_pass(pixel, p);
        return;
    }
    const uint parts = gl_NumWorkGroups.z;
    if (parts == 1u) {
        sum_onto_the_image(pixel, p);
        return;
    }
    const uint pixels = frame.width * frame.height;
    const uint pixel_index = uint(pixel.y) * frame.width + uint(pixel.x);
    if (frame.light_begin == frame.light_end) {
        if (gl_WorkGroupID.z != 0u) return;
        if (kIndirectClamp || kIndirectOff) {
            vec3 radiance = vec3(0.0);
            IndirectSums s = no_indirect_sums();
            for (uint z = 0u; z < parts; ++z) {
                radiance += walk_states[z * pixels + pixel_index].radiance;
                if (kIndirectClamp) merge_indirect_sums(s, indirect_sums_of(walk_states[z * pixels + pixel_index]));
            }
            if (exact_clamp()) {
                begin_exact_clamp(pixel_index, radiance, s);
                return;
            }
            radiance = clamp_indirect(pixel, radiance, s) + classic_and_emitted_radiance(p);
            store_pixel(pixel, radiance, frame.leaf_count, 0u, false);
            return;
        }
        vec3 radiance = classic_and_emitted_radiance(p);
        for (uint z = 0u; z < parts; ++z) radiance += walk_states[z * pixels + pixel_index].radiance;
        store_pixel(pixel, radiance, frame.leaf_count, 0u, false);
        return;
    }
    uint begin, end;
    part_leaves(parts, begin, end);
    const uint at = gl_WorkGroupID.z * pixels + pixel_index;
    vec3 radiance;
    if (kIndirectClamp || kIndirectOff) {
        const vec3 previous = frame.light_begin != 0u ? walk_states[at].radiance : vec3(0.0);
        IndirectSums s;
        radiance = indirect_leaves_onto(previous, at, frame.light_begin == 0u, begin, end, s, p);
    } else {
        radiance = leaves_radiance(begin, end, p);
        if (frame.light_begin != 0u) radiance = walk_states[at].radiance + radiance;
    }
    walk_states[at].radiance = radiance;
    flush_pixel_counters(false);
}

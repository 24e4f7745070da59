// Shadow rays: is a light visible from a shading point? Mirrors
// lightcuts/occlusion/shadow_ray.h (the ray) and ShadowBvh::occluded (the any-hit walk
// over the 4-wide BVH: an inner node pushes the children whose boxes the ray
// hits, the nearest on top for the direction's octant; a leaf tests its
// triangles; the walk ends at the first occluder or an empty stack). kShadows is false when the scene analysis finds that nothing can
// hide a light (scene_effects.cpp); the rays then compile away.
#ifndef LC_SHADOW_RAYS_GLSL
#define LC_SHADOW_RAYS_GLSL

#extension GL_KHR_shader_subgroup_vote : require
#extension GL_KHR_shader_subgroup_ballot : require

#include "common_lighting.glsl"
#include "frame_bindings.glsl"
#include "lightcuts/device/shadow_segment.glsl.h"

layout(constant_id = kSpecShadows) const bool kShadows = false;
// Some occluder is alpha-masked: a hit on it fetches a mask texel.
layout(constant_id = kSpecAlphaMasks) const bool kAlphaMasks = false;

// Beyond any scene: the far end of a ray towards a directional light.
const float kShadowRayFar = 1e30;

// Set when the device's loop limit ended a traversal before it finished (the
// light then counts as visible and the pixel in counters.loop_limit_stops).
bool g_shadow_walk_cut_short = false;
// Rays this invocation traced; added to the frame's counter once per pixel.
uint g_shadow_rays = 0u;
// The triangle that last hid a light from this invocation's point, tested
// before the walk: the rays of one point (and of a subgroup sharing a cut)
// tend to meet the same occluder. -1: none yet.
int g_last_occluder = -1;

// Slab test of a wide node's four child boxes in the ray's parameter. A zero
// direction component was replaced by a tiny one (no 0 * inf); the far
// distance is widened by a few ulps so a flat box (a wall) is never missed
// through rounding.
bvec4 ray_hits_slots(vec3 origin, vec3 inv_direction, float t_max, GpuWideBvhNode node) {
    vec4 x0 = (node.lo_x - origin.x) * inv_direction.x;
    vec4 x1 = (node.hi_x - origin.x) * inv_direction.x;
    vec4 y0 = (node.lo_y - origin.y) * inv_direction.y;
    vec4 y1 = (node.hi_y - origin.y) * inv_direction.y;
    vec4 z0 = (node.lo_z - origin.z) * inv_direction.z;
    vec4 z1 = (node.hi_z - origin.z) * inv_direction.z;
    vec4 enter = max(max(min(x0, x1), min(y0, y1)), max(min(z0, z1), vec4(0.0)));
    vec4 leave = min(min(max(x0, x1), max(y0, y1)), min(max(z0, z1), vec4(t_max))) * 1.000001;
    return lessThanEqual(enter, leave);
}

// Moller-Trumbore, both faces; a hit strictly between the ends of the ray.
// uv: the hit's barycentric weights of the second and third vertices.
bool ray_hits_triangle(vec3 origin, vec3 direction, float t_max, GpuShadowTriangle tri, out vec2 uv) {
    vec3 p = cross(direction, tri.edge2);
    float det = dot(tri.edge1, p);
    uv = vec2(0.0);
    if (det == 0.0) return false;  // the ray lies in the triangle's plane
    float inv_det = 1.0 / det;
    vec3 s = origin - tri.v0;
    float u = dot(s, p) * inv_det;
    vec3 q = cross(s, tri.edge1);
    float v = dot(direction, q) * inv_det;
    float t = dot(tri.edge2, q) * inv_det;
    uv = vec2(u, v);
    return u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t < t_max;
}

// The 8-bit texel of `mask` at uv: nearest, repeat wrap (lightcuts/alpha_mask.cpp).
uint mask_texel(GpuAlphaMask mask, vec2 uv) {
    vec2 wrapped = uv - floor(uv);
    float fx = clamp(wrapped.x * float(mask.width), 0.0, float(mask.width - 1u));
    float fy = clamp(wrapped.y * float(mask.height), 0.0, float(mask.height - 1u));
    uint texel = mask.texel_offset + uint(fy) * mask.width + uint(fx);
    uint word = mask_texels[texel >> 4u].words[(texel >> 2u) & 3u];
    return (word >> (8u * (texel & 3u))) & 0xffu;
}

// Does a hit at barycentrics `bary` block the light? Opaque triangles always
// do; a masked one where its mask keeps the surface.
bool triangle_blocks(GpuShadowTriangle tri, vec2 bary) {
    if (!kAlphaMasks || tri.masked == 0u) return true;
    GpuMaskedTriangle m = masked_triangles[tri.masked - 1u];
    vec2 uv = m.uv0 * (1.0 - bary.x - bary.y) + m.uv1 * bary.x + m.uv2 * bary.y;
    GpuAlphaMask mask = alpha_masks[m.mask];
    return mask_texel(mask, uv) >= mask.keep_threshold;
}

// Any-hit: a hit that the triangle's mask (if any) keeps.
bool ray_blocked_by(vec3 origin, vec3 direction, float t_max, GpuShadowTriangle tri) {
    vec2 bary;
    return ray_hits_triangle(origin, direction, t_max, tri, bary) && triangle_blocks(tri, bary);
}

// The direction's octant as GpuWideBvhNode::order indexes it, one for the
// subgroup (its walk is shared): negative on an axis where any lane's is.
uint walk_octant(vec3 direction, bool searching) {
    return uint(subgroupAny(searching && direction.x < 0.0)) |
           uint(subgroupAny(searching && direction.y < 0.0)) << 1u |
           uint(subgroupAny(searching && direction.z < 0.0)) << 2u;
}

// Pushes a node's slot when any searching lane's ray hits its box, with
// whether this lane's does (ray_occluded's locals; a macro because GLSL
// passes arrays to functions by copy).
#define SHADOW_PUSH_SLOT(slot_expr)                           \
    {                                                         \
        uint slot = (slot_expr);                              \
        bool lane_hit = slot_hits[slot] != 0u;                \
        if (subgroupAny(lane_hit)) {                          \
            if (size < kBvhStackSize) {                       \
                stack[size] = node.children[slot];            \
                stack_entered[size] = lane_hit;               \
                ++size;                                       \
            } else {                                          \
                g_shadow_walk_cut_short = true;               \
            }                                                 \
        }                                                     \
    }

// The subgroup's shared walk: every lane reads the same entry (uniform
// reads, where llvmpipe loads once instead of gathering per lane). An inner
// node pushes each slot that any searching lane's ray hits, farthest first,
// so the nearest pops next; each lane keeps whether its own ray hit the
// slot, and tests a leaf's triangles only then. The build bounds the stack
// (ShadowBvhStats::stack_need <= kBvhStackSize); the size check only guards
// a corrupt upload. `searching` false: this lane needs no ray (it still walks
// with the others).
bool ray_occluded(vec3 origin, vec3 direction, float t_max, bool searching) {
    vec3 safe = mix(direction, vec3(1e-30), equal(direction, vec3(0.0)));
    vec3 inv_direction = 1.0 / safe;
    bool hit = !searching;
    if (searching && g_last_occluder >= 0)
        hit = ray_blocked_by(origin, direction, t_max, shadow_triangles[g_last_occluder]);
    uint octant = walk_octant(direction, !hit);
    uint stack[kBvhStackSize];
    bool stack_entered[kBvhStackSize];
    uint size = 0u;
    uint entry = 0u;  // the root, an inner entry (count 0)
    bool entered = true;
    bool done = false;
    // Each entry is popped once at most: frame.bvh_node_count bounds the steps.
    for (uint step = 0u; !done && subgroupAny(!hit) && step < frame.bvh_node_count; step += kShadowUnroll) {
        uint count = entry & kBvhLeafCountMask;
        uint index = entry >> kBvhLeafCountBits;
        bool testing = entered && !hit;
        if (count == 0u) {
            GpuWideBvhNode node = bvh_nodes[index];
            uvec4 used = uvec4(notEqual(node.children, uvec4(kBvhEmptyChild)));
            uvec4 slot_hits = uvec4(ray_hits_slots(origin, inv_direction, t_max, node)) * used * uint(testing);
            uint order = (node.order[octant >> 2u] >> (8u * (octant & 3u))) & 0xffu;
            // Written out, not a loop: llvmpipe's loop limiter would count a
            // loop's back edges even where the trip count is constant.
            SHADOW_PUSH_SLOT(order >> 6u);
            SHADOW_PUSH_SLOT((order >> 4u) & 3u);
            SHADOW_PUSH_SLOT((order >> 2u) & 3u);
            SHADOW_PUSH_SLOT(order & 3u);
        } else {
            for (uint k = 0u; k < kBvhMaxLeafSize; ++k) {
                if (k < count) {
                    GpuShadowTriangle tri = shadow_triangles[index + k];
                    if (testing && ray_blocked_by(origin, direction, t_max, tri)) {
                        hit = true;
                        g_last_occluder = int(index + k);
                    }
                }
            }
        }
        if (size == 0u) {
            done = true;
        } else {
            --size;
            entry = subgroupBroadcastFirst(stack[size]);
            entered = stack_entered[size];
        }
    }
    if (!hit && !done) g_shadow_walk_cut_short = true;
    return searching && hit;
}

// V in {0, 1} of `light` (or a cluster's representative) from point x with
// unit normal n; call it only where the light's contribution is non-zero.
// The ray's segment: lightcuts/device/shadow_segment.glsl.h (shadow_bias
// along the normal and along the ray, shadow_bias short of a positional light).
// Call it in uniform control flow (every lane of the subgroup): the lanes
// walk the BVH together; `needed` false (a zero contribution) traces nothing.
float light_visibility(GpuLight light, vec3 x, vec3 n, bool needed) {
    if (!kShadows || frame.bvh_node_count == 0u) return 1.0;
    ShadowSegment s = shadow_segment(x, n, light.type == kLightDirectional, light.position, light.direction,
                                     frame.shadow_bias, kShadowRayFar);
    needed = needed && s.traced;
    if (needed) ++g_shadow_rays;
    if (!subgroupAny(needed)) return 1.0;
    return ray_occluded(s.origin, s.direction, s.t_max, needed) ? 0.0 : 1.0;
}

// Adds this invocation's rays to the frame's counter, which is 64-bit: the
// low word, then the carry into the high word.
void flush_shadow_ray_count() {
    if (!kShadows || g_shadow_rays == 0u) return;
    uint before = atomicAdd(counters.shadow_rays, g_shadow_rays);
    if (before + g_shadow_rays < before) atomicAdd(counters.shadow_rays_high, 1u);
    g_shadow_rays = 0u;
}

// I * color * G * V: the shading model's irradiance with the light's visibility
// (`l` as light_irradiance gives it). In uniform control flow, like light_visibility.
vec3 visible_irradiance(GpuLight light, vec3 x, vec3 n, out vec3 l) {
    vec3 e = light_irradiance(light, x, n, l);
    if (kShadows) e *= light_visibility(light, x, n, max(e.x, max(e.y, e.z)) > 0.0);
    return e;
}

#endif

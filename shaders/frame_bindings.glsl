// The compute passes' descriptor set and push constants. Bindings match
// FrameBinding in editor_client/render/renderer.cpp; the push constants mirror
// GpuFrameConstants in gpu_layout.h.
#ifndef LC_FRAME_BINDINGS_GLSL
#define LC_FRAME_BINDINGS_GLSL

#include "gpu_layout.glsl"

layout(set = 0, binding = 0, rgba32f) uniform readonly image2D gbuffer_position;  // w: 1 = geometry
layout(set = 0, binding = 1, rgba32f) uniform readonly image2D gbuffer_normal;    // w: roughness
layout(set = 0, binding = 2, rgba32f) uniform readonly image2D gbuffer_albedo;    // w: metallic
layout(set = 0, binding = 3, rgba32f) uniform readonly image2D gbuffer_emissive;
layout(set = 0, binding = 4, rgba32f) uniform image2D hdr_image;  // linear radiance
layout(set = 0, binding = 5, rg32ui) uniform uimage2D cut_image;  // x: cut size, y: cut hash
layout(set = 0, binding = 6, rgba8) uniform writeonly image2D display_image;  // sRGB-encoded

layout(std430, set = 0, binding = 7) readonly buffer LeafLights { GpuLight leaf_lights[]; };
layout(std430, set = 0, binding = 8) readonly buffer TreeNodes { GpuTreeNode tree_nodes[]; };
layout(std430, set = 0, binding = 9) readonly buffer ClassicLights { GpuLight classic_lights[]; };
layout(std430, set = 0, binding = 10) buffer FrameCounters {
    uint max_cut;
    uint nonfinite_pixels;
    uint geometry_pixels;
    uint max_cut_hits;  // bound criterion: pixels whose cut stopped at max-cut
    uint loop_limit_stops;  // pixels whose walk or shadow ray the device's loop limit cut short
    uint shadow_rays;       // low 32 bits
    uint shadow_rays_high;  // high 32 bits
} counters;
// Per-node box and cone for the bound criterion (GpuNodeBounds, same order as tree_nodes).
layout(std430, set = 0, binding = 11) readonly buffer NodeBounds { GpuNodeBounds node_bounds[]; };
// The shadow-casting triangles and their BVH (editor_client/render/shadow_bvh.h).
layout(std430, set = 0, binding = 12) readonly buffer BvhNodes { GpuBvhNode bvh_nodes[]; };
layout(std430, set = 0, binding = 13) readonly buffer ShadowTriangles { GpuShadowTriangle shadow_triangles[]; };
// The walk search's state per pixel between its passes (row-major pixels).
layout(std430, set = 0, binding = 14) buffer WalkStates { GpuWalkState walk_states[]; };

layout(push_constant) uniform FrameConstants {
    uint width;
    uint height;
    uint leaf_count;
    uint classic_count;
    uint node_count;
    float exposure;
    uint scale_bar_rows;
    float shadow_bias;
    uint light_begin;
    uint light_end;
    uint bvh_node_count;
    uint walk_dispatch;
    vec3 eye;
    float pad2;
} frame;

#endif

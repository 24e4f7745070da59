// The compute passes' descriptor set and push constants; the structs, binding
// numbers and constants come from lightcuts/device/, shared with the C++.
#ifndef LC_FRAME_BINDINGS_GLSL
#define LC_FRAME_BINDINGS_GLSL

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/device/limits.h"
#include "lightcuts/device/spec_constants.h"

layout(set = 0, binding = kBindPosition, rgba32f) uniform readonly image2D gbuffer_position;
layout(set = 0, binding = kBindNormal, rgba32f) uniform readonly image2D gbuffer_normal;
layout(set = 0, binding = kBindAlbedo, rgba32f) uniform readonly image2D gbuffer_albedo;
layout(set = 0, binding = kBindEmissive, rgba32f) uniform readonly image2D gbuffer_emissive;
layout(set = 0, binding = kBindHdr, rgba32f) uniform image2D hdr_image;
layout(set = 0, binding = kBindCut, rg32ui) uniform uimage2D cut_image;
layout(set = 0, binding = kBindDisplay, rgba8) uniform writeonly image2D display_image;

layout(std430, set = 0, binding = kBindLeafLights) readonly buffer LeafLights { GpuLight leaf_lights[]; };
layout(std430, set = 0, binding = kBindTreeNodes) readonly buffer TreeNodes { GpuTreeNode tree_nodes[]; };
layout(std430, set = 0, binding = kBindClassicLights) readonly buffer ClassicLights { GpuLight classic_lights[]; };
layout(std430, set = 0, binding = kBindCounters) buffer FrameCounters { GpuFrameCounters counters; };
// The shadow-casting triangles and their 4-wide BVH (lightcuts/occlusion/shadow_bvh.h).
layout(std430, set = 0, binding = kBindBvhNodes) readonly buffer BvhNodes { GpuWideBvhNode bvh_nodes[]; };
layout(std430, set = 0, binding = kBindShadowTriangles) readonly buffer ShadowTriangles { GpuShadowTriangle shadow_triangles[]; };
// Alpha-masked shadow triangles (lightcuts/alpha_mask.h): texture coordinates, masks, texels.
layout(std430, set = 0, binding = kBindMaskedTriangles) readonly buffer MaskedTriangles { GpuMaskedTriangle masked_triangles[]; };
layout(std430, set = 0, binding = kBindAlphaMasks) readonly buffer AlphaMasks { GpuAlphaMask alpha_masks[]; };
layout(std430, set = 0, binding = kBindMaskTexels) readonly buffer MaskTexels { GpuMaskTexels mask_texels[]; };
// Reference mode's exact clamp: which VPLs' shadow rays were blocked, per pixel.
layout(std430, set = 0, binding = kBindVplVisibility) buffer VplVisibility { GpuVisibilityBits vpl_visibility[]; };
// The walk search's state per pixel between its passes (row-major pixels).
layout(std430, set = 0, binding = kBindWalkStates) buffer WalkStates { GpuWalkState walk_states[]; };
// What pixels without geometry show (shaders/background.glsl).
layout(std430, set = 0, binding = kBindBackground) readonly buffer Background { GpuBackground background; };
layout(std430, set = 0, binding = kBindEnvironmentTexels) readonly buffer EnvironmentTexels {
    GpuEnvironmentTexel environment_texels[];
};

layout(push_constant) uniform FrameConstants { GpuFrameConstants frame; };

#endif

// The structs the shaders read and write (std430 storage buffers and push
// constants), with their flags, written once for C++ and GLSL. Padding is
// explicit so that C++ (glm) and std430 lay them out alike;
// tests/shader_interface_test.cpp checks every offset against the SPIR-V.
#ifndef LC_DEVICE_GPU_STRUCTS_H
#define LC_DEVICE_GPU_STRUCTS_H

#include "lightcuts/device/glsl_compat.h"
#include "lightcuts/device/node_flags.h"

LC_DEVICE_BEGIN

// LightType (scene_light.h) as the shaders compare it.
LC_CONST uint kLightPoint = 0u;
LC_CONST uint kLightSpot = 1u;
LC_CONST uint kLightDirectional = 2u;
LC_CONST uint kLightOriented = 3u;

// Pre-order "next node after my subtree" (tree walks, shadow BVH): past the last node.
LC_CONST int kEndOfWalk = -1;

// GpuLight::flags
LC_CONST uint kGpuLightIndirect = 1u;  // bounced light: clamped (indirect_clamp.glsl.h)
LC_CONST uint kGpuLightPatch = 2u;     // a radiosity patch (with kGpuLightIndirect): a disk, not clamped

// One light, as the shading model evaluates it (shading_model.h): the leaf
// lights (every tree node's representative among them) and the classic lights.
struct LC_ALIGN16 GpuLight {
    vec3 position LC_DEFAULT(vec3(0.0f));
    float range LC_DEFAULT(0.0f);  // 0: unbounded
    vec3 direction LC_DEFAULT(vec3(0.0f, 0.0f, -1.0f));
    uint type LC_DEFAULT(0u);                    // LightType
    vec3 intensity LC_DEFAULT(vec3(0.0f));  // RGB: color x intensity (candela or lux)
    float spot_cos_outer LC_DEFAULT(0.0f);
    float spot_cos_inner LC_DEFAULT(1.0f);
    // 1 / max(cos_inner - cos_outer, kSpotMinCosDelta), precomputed (shading_model.h).
    float spot_scale LC_DEFAULT(1.0f);
    uint flags LC_DEFAULT(0u);  // kGpuLight*
    // A radiosity patch's equivalent disk radius (shading.glsl.h); 0 for every other light.
    float source_radius LC_DEFAULT(0.0f);
};

// A light-tree node as the walks read it, 64 bytes (pbrt-v4's
// CompactLightBounds is the model; made and decoded in lightcuts/tree/compact_node.h).
// A node evaluated as a cluster is its representative leaf light
// (leaf_lights[representative]) with the cluster's intensity, so no light
// parameter is quantised; the bound criterion reads the box and the cone,
// whose axis is octahedral-packed and whose angle is widened to match.
struct LC_ALIGN16 GpuTreeNode {
    vec3 intensity LC_DEFAULT(vec3(0.0f));  // the cluster's RGB intensity
    uint representative LC_DEFAULT(0u);     // index into the leaf lights
    // The leaves' positions (their directions for directional lights).
    vec3 bbox_min LC_DEFAULT(vec3(0.0f));
    int first_child LC_DEFAULT(kNoChild);  // left when present, else right; kNoChild for leaves
    vec3 bbox_max LC_DEFAULT(vec3(0.0f));
    int escape LC_DEFAULT(kEndOfWalk);  // next node in pre-order after this subtree
    float radius LC_DEFAULT(kUnboundedRadius);  // influence radius around the representative; < 0 unbounded
    uint cone_axis LC_DEFAULT(0u);      // the spot directions' cone: octahedral, 2 x snorm16
    float cone_cos LC_DEFAULT(-1.0f);   // its half-angle's cosine, rounded down; -1: every direction
    uint flags LC_DEFAULT(0u);          // node_flags.h: kNodeMixedTypes | kNodeIndirect | kNodePatch |
                                        // kNodeBoundedRepresentative | type << kNodeTypeShift
};

// Counters the lighting pass accumulates with atomics (reset every frame).
struct LC_ALIGN16 GpuFrameCounters {
    uint max_cut LC_DEFAULT(0u);
    uint nonfinite_pixels LC_DEFAULT(0u);
    uint geometry_pixels LC_DEFAULT(0u);
    uint max_cut_hits LC_DEFAULT(0u);  // bound criterion: pixels whose cut stopped at max-cut
    // Pixels whose walk or shadow ray the device's loop limit cut short
    // (llvmpipe, limits.h); the walk search keeps its last complete pass (only
    // when a pass alone exceeds the limit: others run again).
    uint loop_limit_stops LC_DEFAULT(0u);
    // Shadow rays the lighting pass traced: a 64-bit count in two words.
    uint shadow_rays LC_DEFAULT(0u);
    uint shadow_rays_high LC_DEFAULT(0u);
    // Reconstruction cuts: pixels between the samples that ran a full
    // lightcut of their own (a silhouette, a sample over its record cap).
    uint reconstruction_fallbacks LC_DEFAULT(0u);
};

// GpuWalkState::flags; bits kWalkBisectionsShift and up: the bisection passes left.
LC_CONST uint kWalkDone = 1u;
LC_CONST uint kWalkRuleMet = 2u;
LC_CONST uint kWalkBisecting = 4u;
LC_CONST uint kWalkLoopStop = 8u;
LC_CONST uint kWalkStorePending = 16u;  // done where the loop limit fired: stored next dispatch
LC_CONST uint kWalkAlone = 32u;  // shared cuts: the lane left the subgroup's vote (over max-cut through it)
// Reconstruction samples: a shaded pass went over max-cut after the kept cut
// had written its records, so they no longer describe it.
LC_CONST uint kWalkRecordsStale = 64u;
LC_CONST uint kWalkBisectionsShift = 8u;

// One pixel's walk search between dispatches (shaders/lightcuts_bound_walk.comp):
// a pass that llvmpipe's loop limit (limits.h) cuts short runs again in the
// next dispatch, so the limit applies to one pass instead of the whole search.
// The GPU alone reads and writes it; the CPU only sizes the buffer
// (RenderTargets::walk_states).
struct LC_ALIGN16 GpuWalkState {
    vec3 radiance LC_DEFAULT(vec3(0.0f));  // the last cut that fit, f_r applied
    uint size LC_DEFAULT(0u);
    uint hash LC_DEFAULT(0u);
    float tau LC_DEFAULT(0.0f);      // the next pass's threshold
    float fit_hi LC_DEFAULT(0.0f);   // largest bound on the last cut that fit
    float over_lo LC_DEFAULT(0.0f);  // a threshold whose cut exceeded max-cut
    uint flags LC_DEFAULT(0u);       // kWalk*
    uint passes LC_DEFAULT(0u);      // passes completed
    uint pad1 LC_DEFAULT(0u);
    uint pad2 LC_DEFAULT(0u);
    // The last cut's indirect lights (device::IndirectSums, indirect_clamp.glsl.h),
    // clamped when the pixel is stored; reference mode keeps its partial sums
    // here between dispatches. Written only when the tree has indirect lights.
    vec3 indirect_largest LC_DEFAULT(vec3(0.0f));
    uint indirect_leaves LC_DEFAULT(0u);
    vec3 indirect_second LC_DEFAULT(vec3(0.0f));
    // The stored pixel's indirect light before the clamp and what the clamp
    // removed, summed over the channels (render stats: the clamped energy).
    float indirect_energy LC_DEFAULT(0.0f);
    vec3 indirect_rest LC_DEFAULT(vec3(0.0f));
    float clamped_energy LC_DEFAULT(0.0f);
    vec3 indirect_clusters LC_DEFAULT(vec3(0.0f));
    float indirect_rest_max LC_DEFAULT(0.0f);
    vec3 indirect_others LC_DEFAULT(vec3(0.0f));
    uint pad3 LC_DEFAULT(0u);
    // Reference mode's exact clamp (indirect_clamp.glsl.h): the pixel's
    // threshold per channel and how much the last pass moved it (its first
    // part's state), and each part's tally at the threshold over a pass.
    vec3 clamp_threshold LC_DEFAULT(vec3(0.0f));
    float clamp_change LC_DEFAULT(0.0f);
    vec3 clamp_below LC_DEFAULT(vec3(0.0f));  // the lights at most the threshold, summed
    uint pad4 LC_DEFAULT(0u);
    vec3 clamp_above LC_DEFAULT(vec3(0.0f));  // the lights above it, counted
    uint pad5 LC_DEFAULT(0u);
};

// Push constants shared by the compute passes.
struct LC_ALIGN16 GpuFrameConstants {
    uint width LC_DEFAULT(0u);
    uint height LC_DEFAULT(0u);
    uint leaf_count LC_DEFAULT(0u);
    uint classic_count LC_DEFAULT(0u);
    uint node_count LC_DEFAULT(0u);
    float exposure LC_DEFAULT(1.0f);
    uint scale_bar_rows LC_DEFAULT(0u);  // cutsize mode: rows at the bottom for the colour scale
    // Shadow rays start this far along the normal (shadow_ray.h); 0 without shadows.
    float shadow_bias LC_DEFAULT(0.0f);
    // Reference mode sums the leaves [light_begin, light_end) per dispatch, so
    // that no dispatch exceeds llvmpipe's loop budget; the first also adds the
    // classic lights and emission, the last one stores the pixel.
    uint light_begin LC_DEFAULT(0u);
    uint light_end LC_DEFAULT(0u);
    uint bvh_node_count LC_DEFAULT(0u);  // a shadow walk's steps at most: ShadowBvh::walk_steps (0: nothing occludes)
    uint walk_dispatch LC_DEFAULT(0u);   // the bound criterion's walk search: this dispatch's number
    vec3 eye LC_DEFAULT(vec3(0.0f));     // camera position: the glossy lobe's view direction
    // Reference mode's exact clamp: this dispatch's pass over the leaves (0:
    // the sums) of clamp_passes more (0 without clamped leaves).
    uint clamp_pass LC_DEFAULT(0u);
    uint clamp_passes LC_DEFAULT(0u);
    // Reference mode over a lattice of single-workgroup tiles dispatched as one
    // grid (workgroup_lattice.h): workgroup (i, j) lights the image's workgroup
    // lattice_origin + (i, j) x lattice_step. 0: the workgroup is its own place.
    uint lattice_step LC_DEFAULT(0u);
    uint lattice_origin_x LC_DEFAULT(0u);
    uint lattice_origin_y LC_DEFAULT(0u);
    // The real-time mode's frame key (realtime_lighting.comp): what its frames
    // draw independently of each other (the uniforms of worn chains) hashes it.
    uint frame_seed LC_DEFAULT(0u);
    // Reference mode's exact clamp: the sums' pass keeps each VPL's visibility
    // (kBindVplVisibility, this many GpuVisibilityBits per pixel) and Newton's
    // passes read it instead of tracing the ray again; 0: they trace.
    uint vpl_visibility_stride LC_DEFAULT(0u);
    // The real-time mode's frames in order and its seed (render
    // --representative-seed): its uniforms step along Weyl sequences, so a
    // still view's frames spread its draws evenly (frame_strata.glsl).
    uint frame_number LC_DEFAULT(0u);
    uint draw_seed LC_DEFAULT(0u);
};

// Reconstruction cuts (shaders/lightcuts_reconstruction_*.comp): what a
// sample's shadow ray said of a cut node, in the low bits of its record.
LC_CONST uint kSeenDark = 0u;     // the node adds nothing at the sample: no ray was traced
LC_CONST uint kSeenVisible = 1u;  // its representative's ray was clear
LC_CONST uint kSeenBlocked = 2u;  // its ray was blocked
LC_CONST uint kSeenBits = 2u;     // the node index sits above these bits
// GpuReconstructionSample::flags
LC_CONST uint kSampleUsable = 1u;  // its records hold its whole cut (else its blocks fall back)

// One reconstruction sample (a corner of the blocks): its lightcut's tree
// radiance and how many records (one a cut node, in pre-order) it wrote.
struct LC_ALIGN16 GpuReconstructionSample {
    vec3 radiance LC_DEFAULT(vec3(0.0f));  // tree lights, f_r and clamp applied
    uint record_count LC_DEFAULT(0u);
    uint flags LC_DEFAULT(0u);             // kSample*
    // The error ratio its cut reached: the criterion's, or more where max-cut stopped it.
    float reached_ratio LC_DEFAULT(0.0f);
    uint pad1 LC_DEFAULT(0u);
    uint pad2 LC_DEFAULT(0u);
};

// Four cut nodes of a sample, each node index << kSeenBits | kSeen*; a
// sample's records start on a word boundary (its cap rounded up to 4).
struct LC_ALIGN16 GpuCutRecords {
    uvec4 words LC_DEFAULT(uvec4(0u));
};

// 128 bits of kept visibility: bit (leaf & 127) of the pixel's word leaf / 128
// is set where the leaf's shadow ray was blocked.
struct LC_ALIGN16 GpuVisibilityBits {
    uvec4 words LC_DEFAULT(uvec4(0u));
};

// The real-time mode's temporal pass (temporal_accumulate.comp): where each
// pixel's history is in the previous frame, and how much of it to keep.
struct LC_ALIGN16 GpuTemporalParams {
    mat4 previous_view_proj LC_DEFAULT(mat4(1.0f));  // world to the previous frame's clip space
    uint history_valid LC_DEFAULT(0u);  // 0: the history is dropped (first frame, new settings or tree)
    uint camera_moved LC_DEFAULT(0u);   // 0: the same view, the history is the pixel's own
    // Frames of history kept at most: while the view rests (a running mean that
    // converges) and while it moves (a short, clamped history).
    uint still_history_cap LC_DEFAULT(0u);
    uint moving_history_cap LC_DEFAULT(0u);
    // Frames over which the spatial filter fades out as the history grows (0: no filter).
    uint filter_frames LC_DEFAULT(0u);
    float position_tolerance LC_DEFAULT(0.02f);  // reprojection: accepted distance, x the eye distance
    uint pad0 LC_DEFAULT(0u);
    uint pad1 LC_DEFAULT(0u);
};

// The real-time mode's light draw (realtime_lighting.comp) reads one record per
// level of its descent instead of three dependent node loads (the node, its
// first child for the sibling's index, the sibling): record i holds what the
// draw weighs node i's two children by, and where each leads. 48 bytes,
// made from the compact nodes by lightcuts/tree/draw_pairs.h. A child is a node
// index, or ~light (negative) for a leaf: the leaf light the draw ends at.
struct LC_ALIGN16 GpuDrawPair {
    // Each child's bounding sphere of light positions, relative to nothing
    // (world space); radius < 0: the child weighs by its intensity alone (a
    // directional or mixed-type child).
    vec3 centre0 LC_DEFAULT(vec3(0.0f));
    float radius0 LC_DEFAULT(-1.0f);
    vec3 centre1 LC_DEFAULT(vec3(0.0f));
    float radius1 LC_DEFAULT(-1.0f);
    float intensity0 LC_DEFAULT(0.0f);  // scalar (the sum of RGB, representative_scalar)
    float intensity1 LC_DEFAULT(0.0f);  // 0 where node i has one child
    int child0 LC_DEFAULT(0);
    int child1 LC_DEFAULT(0);
};

// GpuBackground::kind: what a pixel without geometry shows.
LC_CONST uint kBackgroundBlack = 0u;  // no environment
LC_CONST uint kBackgroundMap = 1u;    // the equirectangular map (kBindEnvironmentTexels)
LC_CONST uint kBackgroundSky = 2u;    // the Preetham sun and sky (preetham_sky.glsl.h)

// What the lighting passes show where no geometry is hit, rewritten every
// frame (the camera moves; a storage buffer rather than push constants,
// whose 128 bytes the passes share). Pixel (x, y)'s eye ray points along
// ray_at_origin + (x + 0.5) ray_step_x + (y + 0.5) ray_step_y: perspective
// keeps it affine in the pixel, so the frame's jitter and corner grid fit.
struct LC_ALIGN16 GpuBackground {
    vec3 ray_at_origin LC_DEFAULT(vec3(0.0f));  // pixel corner (0, 0), not normalised
    uint kind LC_DEFAULT(kBackgroundBlack);
    vec3 ray_step_x LC_DEFAULT(vec3(0.0f));
    float intensity LC_DEFAULT(1.0f);  // scales the map, the sky and the sun alike
    vec3 ray_step_y LC_DEFAULT(vec3(0.0f));
    float rotation LC_DEFAULT(0.0f);  // the map's, radians (equirect_map.glsl.h)
    vec3 sun_direction LC_DEFAULT(vec3(0.0f, 1.0f, 0.0f));
    float turbidity LC_DEFAULT(3.0f);
    vec3 sun_radiance LC_DEFAULT(vec3(0.0f));  // inside the disc, before intensity
    float sun_cos_radius LC_DEFAULT(1.0f);    // the disc's angular radius, as a cosine
    uint map_width LC_DEFAULT(0u);
    uint map_height LC_DEFAULT(0u);
    uint pad0 LC_DEFAULT(0u);
    uint pad1 LC_DEFAULT(0u);
};

// One texel of the environment map as the background reads it (linear RGB
// radiance), row-major from the zenith row as in lightcuts/equirect_map.h.
struct LC_ALIGN16 GpuEnvironmentTexel {
    vec3 radiance LC_DEFAULT(vec3(0.0f));
    float pad0 LC_DEFAULT(0.0f);
};

// GpuDrawConstants::flags
LC_CONST uint kDrawBaseColorTexture = 1u;
LC_CONST uint kDrawEmissiveTexture = 2u;
LC_CONST uint kDrawMetallicRoughnessTexture = 4u;
LC_CONST uint kDrawAlphaMask = 8u;       // discard where base colour alpha < alpha_cutoff
LC_CONST uint kDrawNormalTexture = 16u;  // a tangent-space normal map, x and y times normal_scale
LC_CONST uint kDrawVertexColors = 32u;   // the mesh's COLOR_0 multiplies the base colour
// glTF doubleSided false: back faces (clockwise as seen) are culled; a
// double-sided surface's back face is shaded with its normal reversed.
LC_CONST uint kDrawSingleSided = 64u;

// Push constants of one G-buffer draw: 128 bytes, Vulkan's guaranteed
// push-constant space.
struct LC_ALIGN16 GpuDrawConstants {
    mat4 view_proj LC_DEFAULT(mat4(1.0f));
    vec4 base_color_factor LC_DEFAULT(vec4(1.0f));
    vec4 emissive_metallic LC_DEFAULT(vec4(0.0f));  // rgb: emissive factor, a: metallic
    vec4 eye_roughness LC_DEFAULT(vec4(0.0f));      // xyz: camera position, w: roughness
    uint flags LC_DEFAULT(0u);                      // kDraw*
    float alpha_cutoff LC_DEFAULT(0.0f);            // with kDrawAlphaMask
    float normal_scale LC_DEFAULT(1.0f);            // with kDrawNormalTexture
    uint pad2 LC_DEFAULT(0u);
};

// Primary visibility cast as rays (shaders/primary_rays.comp; RenderSettings::
// primary): a compute pass writes the G-buffer the raster pass would, from a
// BVH over every triangle (GpuBvhNode, GpuShadowTriangle). Each BVH triangle
// names its three vertices in the scene's vertex array (GpuVertex, 16 floats
// each) and its draw.
struct LC_ALIGN16 GpuPrimaryTriangle {
    uint v0 LC_DEFAULT(0u);
    uint v1 LC_DEFAULT(0u);
    uint v2 LC_DEFAULT(0u);
    uint draw LC_DEFAULT(0u);  // index into the surface materials
};

// The scene's vertex buffer (client::GpuVertex, 16 tightly packed floats:
// position, normal, uv, tangent, colour) as four vec4s for std430.
struct LC_ALIGN16 GpuSceneVertex {
    vec4 position_normal_x LC_DEFAULT(vec4(0.0f));  // xyz: position, w: normal.x
    vec4 normal_yz_uv LC_DEFAULT(vec4(0.0f));       // xy: normal.yz, zw: uv
    vec4 tangent LC_DEFAULT(vec4(0.0f));
    vec4 color LC_DEFAULT(vec4(1.0f));
};

// A draw's material as gbuffer.frag stores it from its draw constants
// (textures are the raster pass's alone: a scene with any stays on raster).
struct LC_ALIGN16 GpuSurfaceMaterial {
    vec4 base_color_factor LC_DEFAULT(vec4(1.0f));
    vec4 emissive_metallic LC_DEFAULT(vec4(0.0f));  // rgb: emissive factor, a: metallic
    float roughness LC_DEFAULT(1.0f);
    uint flags LC_DEFAULT(0u);  // kDrawVertexColors, kDrawSingleSided
    uint pad0 LC_DEFAULT(0u);
    uint pad1 LC_DEFAULT(0u);
};

// The frame's eye rays: clip space back to world space (the raster pass's
// eye_ray_view_projection, inverted), and the camera.
struct LC_ALIGN16 GpuPrimaryParams {
    mat4 inverse_view_proj LC_DEFAULT(mat4(1.0f));
    vec3 eye LC_DEFAULT(vec3(0.0f));
    uint node_count LC_DEFAULT(0u);  // BVH nodes; 0: no triangle
};

// GpuBvhNode::triangles of a leaf: first triangle << kBvhLeafCountBits | count.
LC_CONST uint kBvhLeafCountBits = 3u;
LC_CONST uint kBvhLeafCountMask = (1u << kBvhLeafCountBits) - 1u;
LC_CONST uint kBvhMaxLeafSize = 4u;  // <= kBvhLeafCountMask

// One node of the binary BVH (shadow_bvh.h), pre-order with escapes: primary
// rays walk it for the closest hit (shadow rays walk GpuWideBvhNode).
struct LC_ALIGN16 GpuBvhNode {
    vec3 bbox_min LC_DEFAULT(vec3(0.0f));
    int escape LC_DEFAULT(kEndOfWalk);  // next node in pre-order after this subtree
    vec3 bbox_max LC_DEFAULT(vec3(0.0f));
    // Leaves: first triangle << kBvhLeafCountBits | triangle count (1..kBvhMaxLeafSize);
    // inner nodes: 0 (a count of 0 means "inner": its first child is the next node).
    uint triangles LC_DEFAULT(0u);
};

// The shadow rays' walk (shaders/shadow_rays.glsl, ShadowBvh::occluded): a
// 4-wide BVH whose children are visited nearest-first, pending ones on a stack
// of kBvhStackSize entries; the build guarantees the walk never needs more
// (ShadowBvhStats::stack_need).
LC_CONST uint kBvhWidth = 4u;
LC_CONST uint kBvhStackSize = 48u;
// GpuWideBvhNode::children of an unused slot.
LC_CONST uint kBvhEmptyChild = 0xffffffffu;

// One node of the 4-wide occluder BVH: its children's boxes side by side (a
// slab test of all four in vector form), what each child is, and the order to
// visit them for each sign of the ray's direction.
struct LC_ALIGN16 GpuWideBvhNode {
    vec4 lo_x LC_DEFAULT(vec4(0.0f));
    vec4 hi_x LC_DEFAULT(vec4(0.0f));
    vec4 lo_y LC_DEFAULT(vec4(0.0f));
    vec4 hi_y LC_DEFAULT(vec4(0.0f));
    vec4 lo_z LC_DEFAULT(vec4(0.0f));
    vec4 hi_z LC_DEFAULT(vec4(0.0f));
    // Per slot: a leaf (first triangle << kBvhLeafCountBits | count 1..kBvhMaxLeafSize),
    // an inner child (its node index << kBvhLeafCountBits, count 0) or kBvhEmptyChild.
    uvec4 children LC_DEFAULT(uvec4(kBvhEmptyChild));
    // The slots nearest-first for the direction's octant o (bit 0: x < 0, bit 1:
    // y < 0, bit 2: z < 0): byte o % 4 of order[o / 4], 2 bits a slot, the
    // first in the lowest bits. Unused slots come last.
    uvec4 order LC_DEFAULT(uvec4(0u));
};

// One triangle as the shaders test it (Moller-Trumbore: a vertex and two edges).
struct LC_ALIGN16 GpuShadowTriangle {
    vec3 v0 LC_DEFAULT(vec3(0.0f));
    // 0: opaque; else 1 + its index in the masked triangles (an alpha-masked
    // surface: the ray passes where the mask cuts it out, lightcuts/alpha_mask.h).
    uint masked LC_DEFAULT(0u);
    vec3 edge1 LC_DEFAULT(vec3(0.0f));  // v1 - v0
    float pad1 LC_DEFAULT(0.0f);
    vec3 edge2 LC_DEFAULT(vec3(0.0f));  // v2 - v0
    float pad2 LC_DEFAULT(0.0f);
};

// The texture coordinates of an alpha-masked shadow triangle and its mask.
struct LC_ALIGN16 GpuMaskedTriangle {
    vec2 uv0 LC_DEFAULT(vec2(0.0f));
    vec2 uv1 LC_DEFAULT(vec2(0.0f));
    vec2 uv2 LC_DEFAULT(vec2(0.0f));
    uint mask LC_DEFAULT(0u);  // index into the alpha masks
    uint pad0 LC_DEFAULT(0u);
};

// Sixteen 8-bit mask texels: four to a word, lowest byte first.
struct LC_ALIGN16 GpuMaskTexels {
    uvec4 words LC_DEFAULT(uvec4(0u));
};

// One alpha mask: width x height 8-bit texels (row 0 at v = 0) from texel
// texel_offset on; a texel >= keep_threshold keeps the surface.
struct LC_ALIGN16 GpuAlphaMask {
    uint texel_offset LC_DEFAULT(0u);
    uint width LC_DEFAULT(0u);
    uint height LC_DEFAULT(0u);
    uint keep_threshold LC_DEFAULT(0u);
};

LC_DEVICE_END

#endif

#pragma once
// The light and tree structs as the shaders read them (std430), mirrored field
// for field in shaders/gpu_layout.glsl, and the one place that converts scene
// lights and tree nodes into them. tests/gpu_layout_test.cpp checks sizes and
// offsets; the static_asserts below catch a drift at compile time.
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/light_tree.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"

namespace lc {

// Pre-order "next node after my subtree": -1 past the last node.
inline constexpr int32_t kGpuEndOfWalk = -1;

// GpuTreeNode::flags
inline constexpr uint32_t kGpuNodeMixedTypes = 1u << 0;  // always refined, never a cluster

// One light, as the shading model evaluates it (shading_model.h): the leaf
// lights, the classic lights and the representative of every tree node.
struct alignas(16) GpuLight {
    glm::vec3 position{0.0f};
    float range = 0.0f;  // 0: unbounded
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    uint32_t type = 0;          // LightType
    glm::vec3 intensity{0.0f};  // RGB: color x intensity (candela or lux), or a cluster's sum
    float spot_cos_outer = 0.0f;
    float spot_cos_inner = 1.0f;
    // 1 / max(cos_inner - cos_outer, kSpotMinCosDelta), precomputed (shading_model.h).
    float spot_scale = 1.0f;
    uint32_t pad0 = 0;
    uint32_t pad1 = 0;
};

// A tree node for the stackless walk: the node evaluated as a cluster, plus its
// first child and pre-order escape (the walk needs nothing else to move).
struct alignas(16) GpuTreeNode {
    GpuLight light;
    int32_t first_child = kGpuEndOfWalk;  // left when present, else right; -1 for leaves
    int32_t escape = kGpuEndOfWalk;       // next node in pre-order after this subtree
    float radius = kUnboundedRadius;      // influence radius; < 0 unbounded
    uint32_t flags = 0;
};

// Per-node bounds for the paper's error-bound criterion (binding 11 of the
// compute set; the bound criterion of lightcuts.comp reads them).
struct alignas(16) GpuNodeBounds {
    glm::vec3 bbox_min{0.0f};
    float cone_cos = 1.0f;
    glm::vec3 bbox_max{0.0f};
    float pad0 = 0.0f;
    glm::vec3 cone_axis{0.0f, 0.0f, -1.0f};
    float pad1 = 0.0f;
};

// Counters the lighting pass accumulates with atomics (reset every frame).
struct alignas(16) GpuFrameCounters {
    uint32_t max_cut = 0;
    uint32_t nonfinite_pixels = 0;
    uint32_t geometry_pixels = 0;
    uint32_t max_cut_hits = 0;  // bound criterion: pixels whose cut stopped at max-cut
    // Pixels whose walk or shadow ray the device's loop limit cut short
    // (llvmpipe, loop_limits.glsl); the walk search keeps its last complete
    // pass (only when a pass alone exceeds the limit: others run again).
    uint32_t loop_limit_stops = 0;
    // Shadow rays the lighting pass traced: a 64-bit count in two words.
    uint32_t shadow_rays = 0;
    uint32_t shadow_rays_high = 0;
    uint32_t pad = 0;
};

// One pixel's walk search between dispatches (shaders/lightcuts.comp): a pass
// that llvmpipe's loop limit (loop_limits.glsl) cuts short runs again in the
// next dispatch, so the limit applies to one pass instead of the whole search.
// The GPU alone reads and writes it; the CPU only sizes the buffer
// (RenderTargets::walk_states).
struct alignas(16) GpuWalkState {
    glm::vec3 radiance{0.0f};  // the last cut that fit, f_r applied
    uint32_t size = 0;
    uint32_t hash = 0;
    float tau = 0.0f;      // the next pass's threshold
    float fit_hi = 0.0f;   // largest bound on the last cut that fit
    float over_lo = 0.0f;  // a threshold whose cut exceeded max-cut
    // Bits (kWalk* in shaders/gpu_layout.glsl): done, rule met, bisecting,
    // loop-limit stop, store pending; bits 8..15 the bisection passes left.
    uint32_t flags = 0;
    uint32_t passes = 0;  // passes completed
    uint32_t pad1 = 0;
    uint32_t pad2 = 0;
};

// Push constants shared by the compute passes.
struct alignas(16) GpuFrameConstants {
    uint32_t width = 0;
    uint32_t height = 0;
    uint32_t leaf_count = 0;
    uint32_t classic_count = 0;
    uint32_t node_count = 0;
    float exposure = 1.0f;
    uint32_t scale_bar_rows = 0;  // cutsize mode: rows at the bottom for the colour scale
    // Shadow rays start this far along the normal (shadow_ray.h); 0 without shadows.
    float shadow_bias = 0.0f;
    // Reference mode sums the leaves [light_begin, light_end) per dispatch, so
    // that no dispatch exceeds llvmpipe's loop budget; the first also adds the
    // classic lights and emission, the last one stores the pixel.
    uint32_t light_begin = 0;
    uint32_t light_end = 0;
    uint32_t bvh_node_count = 0;  // shadow BVH nodes (0: nothing occludes)
    uint32_t walk_dispatch = 0;   // the bound criterion's walk search: this dispatch's number
    glm::vec3 eye{0.0f};  // camera position: the glossy lobe's view direction
    float pad2 = 0.0f;
};

// Push constants of one G-buffer draw (shaders/draw_constants.glsl).
inline constexpr uint32_t kDrawBaseColorTexture = 1u << 0;
inline constexpr uint32_t kDrawEmissiveTexture = 1u << 1;
inline constexpr uint32_t kDrawMetallicRoughnessTexture = 1u << 2;
struct alignas(16) GpuDrawConstants {
    glm::mat4 view_proj{1.0f};
    glm::vec4 base_color_factor{1.0f};
    glm::vec4 emissive_metallic{0.0f};  // rgb: emissive factor, a: metallic
    glm::vec4 eye_roughness{0.0f};      // xyz: camera position, w: roughness
    uint32_t flags = 0;
    uint32_t pad0 = 0;
    uint32_t pad1 = 0;
    uint32_t pad2 = 0;
};

static_assert(sizeof(GpuLight) == 64);
static_assert(offsetof(GpuLight, position) == 0);
static_assert(offsetof(GpuLight, range) == 12);
static_assert(offsetof(GpuLight, direction) == 16);
static_assert(offsetof(GpuLight, type) == 28);
static_assert(offsetof(GpuLight, intensity) == 32);
static_assert(offsetof(GpuLight, spot_cos_outer) == 44);
static_assert(offsetof(GpuLight, spot_cos_inner) == 48);
static_assert(offsetof(GpuLight, spot_scale) == 52);
static_assert(sizeof(GpuTreeNode) == 80);
static_assert(offsetof(GpuTreeNode, first_child) == 64);
static_assert(offsetof(GpuTreeNode, escape) == 68);
static_assert(offsetof(GpuTreeNode, radius) == 72);
static_assert(offsetof(GpuTreeNode, flags) == 76);
static_assert(sizeof(GpuNodeBounds) == 48);
static_assert(offsetof(GpuNodeBounds, cone_cos) == 12);
static_assert(offsetof(GpuNodeBounds, bbox_max) == 16);
static_assert(offsetof(GpuNodeBounds, cone_axis) == 32);
static_assert(sizeof(GpuFrameCounters) == 32);
static_assert(offsetof(GpuFrameCounters, loop_limit_stops) == 16);
static_assert(offsetof(GpuFrameCounters, shadow_rays) == 20);
static_assert(sizeof(GpuWalkState) == 48);
static_assert(offsetof(GpuWalkState, size) == 12);
static_assert(offsetof(GpuWalkState, tau) == 20);
static_assert(offsetof(GpuWalkState, flags) == 32);
static_assert(sizeof(GpuFrameConstants) == 64);
static_assert(offsetof(GpuFrameConstants, walk_dispatch) == 44);
static_assert(offsetof(GpuFrameConstants, eye) == 48);
static_assert(offsetof(GpuFrameConstants, shadow_bias) == 28);
static_assert(offsetof(GpuFrameConstants, light_begin) == 32);
static_assert(offsetof(GpuFrameConstants, bvh_node_count) == 40);
static_assert(offsetof(GpuFrameConstants, exposure) == 20);
static_assert(offsetof(GpuFrameConstants, scale_bar_rows) == 24);
static_assert(sizeof(GpuDrawConstants) == 128);  // Vulkan's guaranteed push-constant space
static_assert(offsetof(GpuDrawConstants, base_color_factor) == 64);
static_assert(offsetof(GpuDrawConstants, emissive_metallic) == 80);
static_assert(offsetof(GpuDrawConstants, eye_roughness) == 96);
static_assert(offsetof(GpuDrawConstants, flags) == 112);

// A scene light (glTF units) as the shader evaluates it.
GpuLight make_gpu_light(const SceneLight& light);
// A tree node evaluated as a cluster: its representative's parameters with
// the cluster's RGB intensity.
GpuLight make_gpu_cluster_light(const LightTreeNode& node);

// Pre-order escape index of every node, computed iteratively in one pass over
// the breadth-first order (a parent always precedes its children). Fails on a
// child index that is out of range, not greater than its parent's, or shared.
Result<std::vector<int32_t>> derive_escape_indices(const LightTree& tree);

// Everything the GPU reads about a tree.
struct GpuTree {
    std::vector<GpuTreeNode> nodes;
    std::vector<GpuLight> leaves;  // the tree's leaves in index order (reference mode)
    uint32_t depth = 0;            // longest root-to-leaf path, in edges
};

Result<GpuTree> make_gpu_tree(const LightTree& tree);
std::vector<GpuNodeBounds> make_gpu_node_bounds(const LightTree& tree);

}  // namespace lc

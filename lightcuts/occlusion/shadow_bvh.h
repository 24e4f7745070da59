#pragma once
// The occluders for shadow rays: the scene's shadow-casting triangles in a
// bounding volume hierarchy, answered on the CPU in double precision and
// uploaded for the shaders. The build is binned SAH (in parallel, the same
// nodes at any thread count) into a binary tree, kept in a stackless
// pre-order layout with escapes (primary rays walk it for the closest hit),
// and collapsed into a 4-wide tree (wide_bvh.h) that shadow rays walk any-hit,
// children nearest-first by the ray's direction, on a stack of at most
// kBvhStackSize entries. GpuBvhNode, GpuWideBvhNode and GpuShadowTriangle are
// in lightcuts/device/gpu_structs.h, shared with the shaders.
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/alpha_mask.h"
#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/scene.h"

namespace lc {

// Statistics for logs and stats JSON.
struct ShadowBvhStats {
    uint32_t triangles = 0;            // shadow-casting triangles kept
    uint32_t skipped_degenerate = 0;   // zero-area or non-finite triangles dropped
    uint32_t skipped_non_casting = 0;  // triangles of materials that cast no shadow
    uint32_t masked = 0;               // kept triangles a ray may pass through (alpha masks)
    uint32_t nodes = 0;  // binary
    uint32_t depth = 0;  // longest root-to-leaf path, in edges
    uint32_t wide_nodes = 0;
    uint32_t wide_leaves = 0;
    uint32_t wide_depth = 0;
    uint32_t stack_need = 0;     // most entries the any-hit walk's stack holds (<= kBvhStackSize)
    uint32_t max_sah_depth = 0;  // past it, object medians (lowered until stack_need fits)
};

class ShadowBvh {
public:
    // Every triangle of every mesh whose material casts shadows
    // (Material::casts_shadows), alpha-masked ones with their masks.
    // Deterministic: the same scene gives the same nodes.
    static ShadowBvh build(const Scene& scene);
    // From a flat triangle list (3 vertices per triangle), for tests and tools.
    static ShadowBvh build(std::span<const glm::vec3> triangle_vertices);
    // The same, where `masks` names the alpha-masked triangles (by input index).
    static ShadowBvh build(std::span<const glm::vec3> triangle_vertices, const OccluderMasks& masks);

    bool empty() const { return nodes_.empty(); }
    const ShadowBvhStats& stats() const { return stats_; }

    // Any triangle hit at origin + t * direction with 0 < t < t_max?
    // `direction` need not be unit length (t is in its units). Both faces
    // occlude; an alpha-masked triangle only where its mask keeps it.
    bool occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_max) const;

    // The binary stackless layout (node 0 is the root), for closest-hit walks.
    const std::vector<GpuBvhNode>& gpu_nodes() const { return nodes_; }
    // The 4-wide layout the shadow rays walk (node 0 is the root).
    const std::vector<GpuWideBvhNode>& gpu_wide_nodes() const { return wide_nodes_; }
    // Most loop steps of one shadow ray's walk: every wide node and every leaf once.
    uint32_t walk_steps() const { return stats_.wide_nodes + stats_.wide_leaves; }
    const std::vector<GpuShadowTriangle>& gpu_triangles() const { return triangles_; }
    // The alpha-masked triangles (GpuShadowTriangle::masked - 1 indexes them),
    // their masks and the masks' texels; empty when every triangle is opaque.
    const std::vector<GpuMaskedTriangle>& gpu_masked_triangles() const { return gpu_masked_; }
    const std::vector<GpuAlphaMask>& gpu_alpha_masks() const { return gpu_masks_; }
    const std::vector<GpuMaskTexels>& gpu_mask_texels() const { return gpu_texels_; }
    // Each leaf-order triangle's index in the input list (degenerate ones are
    // dropped): primary rays find a hit triangle's vertices through it.
    const std::vector<uint32_t>& leaf_sources() const { return sources_; }

private:
    void attach_masks(const OccluderMasks& masks, std::span<const uint32_t> source_of_leaf);
    bool blocks(size_t leaf_triangle, double u, double w) const;

    std::vector<GpuBvhNode> nodes_;
    std::vector<GpuWideBvhNode> wide_nodes_;
    std::vector<GpuShadowTriangle> triangles_;  // in leaf order
    std::vector<glm::dvec3> vertices_;          // 3 per triangle, in leaf order, for the CPU test
    std::vector<uint32_t> sources_;             // input triangle of each, in leaf order
    std::vector<AlphaMask> masks_;
    std::vector<GpuMaskedTriangle> gpu_masked_;  // the CPU test reads them too
    std::vector<GpuAlphaMask> gpu_masks_;
    std::vector<GpuMaskTexels> gpu_texels_;
    ShadowBvhStats stats_;
};

}  // namespace lc

#pragma once
// The CPU evaluator: the same estimators as the shaders, in double precision,
// over the same walk tree (walk_tree.h: the compact nodes and leaf lights the
// shaders read). Ground truth for tests and the exact reference for error
// measurements.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/scene_light.h"
#include "lightcuts/tree/walk_tree.h"

namespace lc {

class ShadowBvh;

struct SurfacePoint {
    glm::dvec3 position{0.0};
    glm::dvec3 normal{0.0, 0.0, 1.0};  // unit
    glm::dvec3 albedo{1.0};           // linear diffuse albedo
    // The glossy lobe (material_model.h): F0 (0: none), exponent n, and its
    // axis, the view's mirror direction (unit).
    glm::dvec3 specular{0.0};
    double exponent = 0.0;
    glm::dvec3 mirror{0.0, 0.0, 1.0};
    // What may hide a light from this point (null: nothing, V = 1), and how
    // far its shadow rays start along the normal (shadow_ray.h). A light, or
    // a cluster's representative, whose contribution is not zero is shaded
    // with its visibility.
    const ShadowBvh* occluders = nullptr;
    double shadow_bias = 0.0;
    // The image pixel it shades: per-pixel representatives draw from it
    // (Representatives::kPixel).
    glm::uvec2 pixel{0u};
};

enum class CutCriterion : uint8_t { kRadius = 0, kBound = 1 };

// How the bound criterion finds its cut (both stop under the same rule: every
// cut node's error bound <= error_ratio x the cut's total estimate, or max_cut).
//   kWalk: threshold passes (bound_walk.h); the default, fast on SIMD devices.
//   kHeap: the paper's refinement order, the largest bound first, in a heap.
enum class BoundSearch : uint8_t { kWalk = 0, kHeap = 1 };

// Which leaf light evaluates a cluster (paper Eq. 2's representative).
//   kTree: the node's own, drawn once by the builder for the whole image.
//   kPixel: drawn per pixel with the same probabilities (I_leaf / I_C) by a
//     descent of the cluster's subtree (device/pixel_representative.glsl.h):
//     each pixel's estimate is distributed as before, but its errors are
//     independent of its neighbours' (Stochastic Lightcuts' choice).
//   kImportance: drawn per pixel in proportion to intensity x a cheap bound
//     of cos / d^2 at the point (device::importance_geometry), the estimate
//     the leaf's intensity over its probability (unbiased per channel).
// The values are device::kRepresentatives*, the shaders' constant.
enum class Representatives : uint8_t { kTree = 0, kPixel = 1, kImportance = 2 };

// Default maximum cut size for the bound criterion (the paper's 1000).
inline constexpr uint32_t kDefaultMaxCut = 1000;

struct CutSettings {
    CutCriterion criterion = CutCriterion::kRadius;
    double error_ratio = 0.02;
    uint32_t max_cut = kDefaultMaxCut;
    BoundSearch search = BoundSearch::kWalk;
    // Indirect lights (kNodeIndirect, kGpuLightIndirect) on: their leaves are clamped
    // to half the error ratio of the pixel (device/indirect_clamp.glsl.h);
    // off: every indirect node is left out of the cut (render --indirect off).
    bool indirect = true;
    // The clusters' representatives, and the per-pixel draws' seed.
    Representatives representatives = Representatives::kTree;
    uint32_t representative_seed = 0;
};

// The automatic clamp's ratio: an indirect light contributes at most this
// fraction of the pixel's total, per channel (the paper's half the error ratio).
double indirect_clamp_ratio(double error_ratio);

struct CutResult {
    glm::dvec3 radiance{0.0};
    uint32_t cut_size = 0;     // tree nodes in the cut (classic lights not counted)
    uint32_t cut_hash = 0;     // see cut_hash_term(); equal cuts have equal hashes
    bool max_cut_hit = false;  // the bound criterion stopped at max_cut
    uint32_t passes = 0;       // threshold passes walked (BoundSearch::kWalk)
    // The cut's indirect light before the clamp, and what the clamp removed
    // (shade_lightcuts; radiance is already clamped).
    glm::dvec3 indirect{0.0};
    glm::dvec3 clamped{0.0};
};

// Order-independent identity of a cut: the sum (mod 2^32) of cut_hash_term(i)
// over its node indices i. The shaders compute the same.
uint32_t cut_hash_term(uint32_t node_index);

// The key every per-pixel draw at p starts from (its pixel and the seed).
uint32_t pixel_representative_key(const SurfacePoint& p, const CutSettings& settings);
// The leaf node reached by the per-pixel draw with `key` from node `index`
// in proportion to intensity (the node itself when it is a leaf): the
// pixel's representative of it (kPixel).
int32_t pixel_representative(const WalkTree& tree, int32_t index, uint32_t key);
// A leaf drawn at p from node `index` under the settings' representatives:
// its light (an index into tree.leaves), with the probability it was drawn
// with (1 for kTree, whose leaf is the node's own representative).
struct PixelDraw {
    uint32_t light = 0;
    double probability = 1.0;
};
PixelDraw pixel_draw(const WalkTree& tree, int32_t index, const SurfacePoint& p, const CutSettings& settings);
// Node `index` evaluated as a cluster at p through the settings'
// representative: shade_node() for kTree, the pixel's leaf with the
// cluster's intensity for kPixel, the drawn leaf's light over its
// probability for kImportance.
glm::dvec3 shade_cluster(const WalkTree& tree, int32_t index, const SurfacePoint& p,
                         const CutSettings& settings);

// Outgoing radiance at p from one light (shading_model.h), exact.
glm::dvec3 shade_light(const SceneLight& light, const SurfacePoint& p);
// The same for a leaf light of the walk tree, with its own intensity.
glm::dvec3 shade_light(const GpuLight& light, const SurfacePoint& p);
// Node `index` evaluated as a cluster: its representative leaf light's
// position, direction, range and spot cone, with the cluster's RGB intensity.
glm::dvec3 shade_node(const WalkTree& tree, int32_t index, const SurfacePoint& p);
// The exact sum over every light given.
glm::dvec3 shade_reference(std::span<const SceneLight> lights, const SurfacePoint& p);
// The exact sum over the tree's leaves (what the tree represents).
glm::dvec3 shade_tree_leaves(const WalkTree& tree, const SurfacePoint& p);
// Upper bound, per channel, on the exact contribution at p of every light under
// node `index` and on its cluster estimate (so on the cluster's error): material
// bound x geometric bound (visibility = 1) x cluster RGB intensity. Used by the
// bound criterion; +inf for mixed-type junctions, which are always refined.
// The box and cone are decoded from the compact node (decode_bounds).
glm::dvec3 node_contribution_bound(const WalkTree& tree, int32_t index, const SurfacePoint& p);
// f_r at p towards the unit direction l: albedo / pi plus the glossy lobe
// (material_model.h).
glm::dvec3 material_response(const SurfacePoint& p, const glm::dvec3& l);
// Upper bound, per channel, of the material's f_r at p over every light of the
// node: the diffuse term plus the lobe at the largest cosine between the
// mirror direction and a direction to the node's box (paper Sec. 4.1).
glm::dvec3 material_bound(const WalkTree& tree, int32_t index, const SurfacePoint& p);
// One node of a cut with its cluster estimate (paper Eq. 2, visibility included).
struct CutNodeEstimate {
    int32_t node = 0;
    glm::dvec3 estimate{0.0};
};
// The bound criterion's heap search (BoundSearch::kHeap; classic lights not
// included), with the cut's nodes appended to `nodes` when given (the
// samples of reconstruction cuts are made from them).
CutResult bound_heap_cut(const WalkTree& tree, const SurfacePoint& p, const CutSettings& settings,
                         std::vector<CutNodeEstimate>* nodes = nullptr);
// Reference mode: every leaf of the tree, exact, its indirect leaves clamped
// exactly (exact_indirect_clamp.h; left out with settings.indirect off), plus
// the classic lights. cut_size counts the leaves.
CutResult shade_tree_reference(const WalkTree& tree, std::span<const SceneLight> classic_lights,
                               const SurfacePoint& p, const CutSettings& settings);
// Lightcuts over the tree, plus the classic lights shaded one by one, with the
// indirect leaves clamped (or indirect light left out, settings.indirect).
CutResult shade_lightcuts(const WalkTree& tree, std::span<const SceneLight> classic_lights,
                          const SurfacePoint& p, const CutSettings& settings);

}  // namespace lc

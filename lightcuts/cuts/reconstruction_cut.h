#pragma once
// Reconstruction cuts (Walter et al. 2005, Sec. 7): lightcuts computed at
// sparse samples are turned into impostor directional lights, and a point
// between the samples is shaded by a top-down walk of the light tree that
// discards a node every sample saw as dark, interpolates a node the samples
// agree on (no shadow ray), and otherwise evaluates clusters as a lightcut
// does, with their shadow rays. Shadow rays are then traced only where the
// samples disagree (a shadow edge, a highlight).
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/tree/walk_tree.h"

namespace lc {

// The most samples one reconstruction cut interpolates (a block's corners).
inline constexpr int kMaxReconstructionSamples = 4;

// A tree node as one sample recorded it: an impostor directional light from
// `direction` whose intensity `gamma` reproduces the node's radiance estimate
// at the sample (Eq. 5); `Gamma` is the sample's total in the same units
// (Eq. 6), for relative thresholds.
struct Impostor {
    glm::dvec3 direction{0.0, 0.0, 1.0};
    glm::dvec3 gamma{0.0};
    double Gamma = 0.0;
    bool on_cut = false;  // the node is on the sample's lightcut
    bool usable = true;   // false where the material term vanished (no direction to reuse)
};

// No slot: the node lies below the sample's cut.
inline constexpr int32_t kBelowCut = -1;

// One node on or above a sample's cut, and where its children's records are
// (the paper's layout: records with offsets to their children, no lookup).
struct SampleNode {
    Impostor impostor;
    int32_t children[2] = {kBelowCut, kBelowCut};  // in children_of's order
};

// A lightcut at one point, processed for interpolation: a record for every
// node on or above its cut, the root's first.
struct ReconstructionSample {
    SurfacePoint point;
    glm::dvec3 radiance{0.0};  // the lightcut's estimate (tree lights only)
    uint32_t cut_size = 0;
    std::vector<SampleNode> nodes;
};

// Shadow rays traced, counted the paper's way: one per cluster evaluated
// whose contribution without visibility is not zero.
struct ShadowRayCount {
    uint64_t rays = 0;
};

// The bound criterion's lightcut at p (heap search, tree lights only), its
// shadow rays counted in `rays`; the cut's nodes appended to `nodes` when given.
CutResult counted_lightcut(const WalkTree& tree, const SurfacePoint& p, const CutSettings& settings,
                           ShadowRayCount& rays, std::vector<CutNodeEstimate>* nodes = nullptr);

// counted_lightcut at p, processed into the sample reconstruction cuts read.
ReconstructionSample make_reconstruction_sample(const WalkTree& tree, const SurfacePoint& p,
                                                const CutSettings& settings, ShadowRayCount& rays);

// What the samples (with weights summing to 1, at most kMaxReconstructionSamples)
// predict for the tree's lights at p, by the paper's four rules: discard,
// interpolate, cluster evaluate, refine. `error_ratio` is the lightcut's.
glm::dvec3 reconstruction_cut(const WalkTree& tree, const SurfacePoint& p,
                              std::span<const ReconstructionSample* const> samples,
                              std::span<const double> weights, double error_ratio, ShadowRayCount& rays);

}  // namespace lc

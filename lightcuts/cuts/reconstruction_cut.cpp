#include "lightcuts/cuts/reconstruction_cut.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <numbers>
#include <utility>
#include <vector>

#include "lightcuts/cuts/cut_traversal.h"
#include "lightcuts/material_model.h"
#include "lightcuts/occlusion/shadow_ray.h"

namespace lc {
namespace {

// A cluster evaluation this many times brighter than the samples predict (or
// than the threshold, for nodes they saw as nearly dark) is refined instead:
// the paper's third refinement, which gives no factor.
constexpr double kMuchBrighter = 2.0;

// Unit direction from x towards a node's representative.
glm::dvec3 direction_to(const GpuLight& representative, const glm::dvec3& x) {
    if (LightType(representative.type) == LightType::kDirectional)
        return -glm::normalize(glm::dvec3(representative.direction));
    const glm::dvec3 to_light = glm::dvec3(representative.position) - x;
    const double distance = glm::length(to_light);
    return distance > 0.0 ? to_light / distance : glm::dvec3(0.0, 0.0, 1.0);
}

// The impostor's material term M (Eq. 5): f_r times the cosine at the surface
// (an impostor's geometric term is 1).
glm::dvec3 material_term(const SurfacePoint& p, const glm::dvec3& d) {
    return material_response(p, d) * std::max(glm::dot(p.normal, d), 0.0);
}

// An estimate L from direction d as an impostor of the sample at p.
Impostor make_impostor(const SurfacePoint& p, const glm::dvec3& d, const glm::dvec3& L,
                       const glm::dvec3& total) {
    Impostor imp;
    imp.direction = d;
    const glm::dvec3 M = material_term(p, d);
    // A lobe that is zero in this direction (a metal away from its
    // highlight) says nothing of the same node seen from another view.
    if (glm::dot(p.normal, d) > 0.0 && max_channel(M) <= 0.0) imp.usable = false;
    for (int c = 0; c < 3; ++c) {
        if (M[c] > 0.0) {
            imp.gamma[c] = L[c] / M[c];
            imp.Gamma = std::max(imp.Gamma, total[c] / M[c]);
        } else if (L[c] > 0.0) {
            imp.usable = false;
        }
    }
    return imp;
}

// The paper keeps impostors out of glossy highlights: f_r above the largest
// diffuse value, 1/pi. Our lobes also sit on dark or metallic bases (a brushed
// steel cabinet), where f_r stays under 1/pi inside the lobe, so a direction
// where the lobe outweighs the diffuse term counts as inside too.
bool inside_gloss_lobe(const SurfacePoint& p, const glm::dvec3& f_r) {
    const glm::dvec3 diffuse = p.albedo * std::numbers::inv_pi;
    return max_channel(f_r) > std::numbers::inv_pi * (1.0 + 1e-9) ||
           max_channel(f_r - diffuse) > max_channel(diffuse);
}

// Nothing blocks this copy of p: its shading says whether a ray would be traced.
SurfacePoint without_occluders(const SurfacePoint& p) {
    SurfacePoint open = p;
    open.occluders = nullptr;
    return open;
}

// A cluster evaluated as a lightcut does (Eq. 2), its shadow ray counted.
// The shaded value with visibility is the open one times V in {0, 1}
// (cpu_evaluator's unit_response), so the ray is traced on its own.
glm::dvec3 evaluate_cluster(const WalkTree& tree, int32_t index, const SurfacePoint& p,
                            const SurfacePoint& open, ShadowRayCount& rays) {
    const glm::dvec3 unshadowed = shade_node(tree, index, open);
    if (max_channel(unshadowed) <= 0.0) return glm::dvec3(0.0);
    if (p.occluders == nullptr) return unshadowed;
    ++rays.rays;
    const GpuLight& light = tree.light_of(index);
    const double visible =
        light_visibility(*p.occluders, p.shadow_bias, LightType(light.type), glm::dvec3(light.position),
                         glm::dvec3(light.direction), p.position, p.normal);
    return visible > 0.0 ? unshadowed : glm::dvec3(0.0);
}

// Where one sample's record of a walked node is: its own slot, or below the
// cut its ancestor's on the cut, whose impostor lends its direction with the
// intensity scaled by the ratio of the clusters' intensities.
struct SampleRef {
    int32_t slot = 0;
    double scale = 1.0;
    bool below = false;
};

struct WalkEntry {
    int32_t node = 0;
    std::array<SampleRef, kMaxReconstructionSamples> refs;
};

double intensity_ratio(const GpuTreeNode& child, const GpuTreeNode& parent) {
    const double parent_intensity = max_channel(glm::dvec3(parent.intensity));
    return parent_intensity > 0.0 ? max_channel(glm::dvec3(child.intensity)) / parent_intensity
                                  : 0.0;
}

}  // namespace

CutResult counted_lightcut(const WalkTree& tree, const SurfacePoint& p, const CutSettings& settings,
                           ShadowRayCount& rays, std::vector<CutNodeEstimate>* nodes) {
    if (tree.empty()) return {};
    std::vector<CutNodeEstimate> cut;
    const CutResult result = bound_heap_cut(tree, p, settings, &cut);
    if (p.occluders != nullptr) {
        // A node lit through its shadow ray had a ray; only a dark one is
        // shaded again, open, to tell a blocked ray from no ray.
        const SurfacePoint open = without_occluders(p);
        for (const CutNodeEstimate& entry : cut) {
            if (max_channel(entry.estimate) > 0.0 || max_channel(shade_node(tree, entry.node, open)) > 0.0)
                ++rays.rays;
        }
    }
    if (nodes != nullptr) *nodes = std::move(cut);
    return result;
}

ReconstructionSample make_reconstruction_sample(const WalkTree& tree, const SurfacePoint& p,
                                                const CutSettings& settings, ShadowRayCount& rays) {
    ReconstructionSample sample;
    sample.point = p;
    if (tree.empty()) return sample;
    std::vector<CutNodeEstimate> cut;
    const CutResult result = counted_lightcut(tree, p, settings, rays, &cut);
    sample.radiance = result.radiance;
    sample.cut_size = result.cut_size;

    // Which tree nodes are on the cut (1 + their index in `cut`), in a buffer
    // kept per thread and cleared after use.
    thread_local std::vector<uint32_t> on_cut;
    if (on_cut.size() < tree.nodes.size()) on_cut.assign(tree.nodes.size(), 0);
    for (size_t k = 0; k < cut.size(); ++k) on_cut[size_t(cut[k].node)] = uint32_t(k + 1);

    // Records in pre-order from the root, down to the cut (an explicit stack).
    struct Pending {
        int32_t node, parent_slot, child_position;
    };
    std::vector<Pending> stack{{0, -1, 0}};
    std::vector<glm::dvec3> L, d;  // per record: the estimate and its direction
    // A binary tree's nodes on and above a cut of n nodes: at most 2n - 1.
    const size_t records = 2 * cut.size();
    sample.nodes.reserve(records);
    L.reserve(records);
    d.reserve(records);
    while (!stack.empty()) {
        const Pending next = stack.back();
        stack.pop_back();
        const int32_t slot = int32_t(sample.nodes.size());
        sample.nodes.emplace_back();
        if (next.parent_slot >= 0)
            sample.nodes[size_t(next.parent_slot)].children[next.child_position] = slot;
        if (const uint32_t k = on_cut[size_t(next.node)]; k > 0) {
            sample.nodes.back().impostor.on_cut = true;
            L.push_back(cut[k - 1].estimate);
            d.push_back(direction_to(tree.light_of(next.node), p.position));
            continue;
        }
        L.emplace_back(0.0);
        d.emplace_back(0.0);
        int32_t children[2];
        const int child_count = children_of(tree, next.node, children);
        for (int c = child_count - 1; c >= 0; --c) stack.push_back({children[c], slot, c});
    }
    for (const CutNodeEstimate& entry : cut) on_cut[size_t(entry.node)] = 0;

    // Above the cut, children before parents (reverse pre-order): the sum of
    // the children's estimates, and their directions weighted by them.
    for (size_t r = sample.nodes.size(); r-- > 0;) {
        SampleNode& record = sample.nodes[r];
        if (record.impostor.on_cut) continue;
        glm::dvec3 weighted(0.0), plain(0.0);
        for (int32_t child : record.children) {
            if (child == kBelowCut) continue;
            L[r] += L[size_t(child)];
            weighted += max_channel(L[size_t(child)]) * d[size_t(child)];
            plain += d[size_t(child)];
        }
        const glm::dvec3 sum = glm::length(weighted) > 0.0 ? weighted : plain;
        d[r] = glm::length(sum) > 0.0 ? glm::normalize(sum) : p.normal;
    }
    for (size_t r = 0; r < sample.nodes.size(); ++r) {
        const bool cut_node = sample.nodes[r].impostor.on_cut;
        sample.nodes[r].impostor = make_impostor(p, d[r], L[r], result.radiance);
        sample.nodes[r].impostor.on_cut = cut_node;
    }
    return sample;
}

namespace {

// A node's impostors at the samples, and what the walk's rules compare.
struct NodeAtSamples {
    std::array<const Impostor*, kMaxReconstructionSamples> imp{};
    std::array<glm::dvec3, kMaxReconstructionSamples> gamma{};
    glm::dvec3 hi{0.0}, lo{0.0};
    double gamma_max = 0.0, gamma_min = 0.0, smallest_total = 0.0;
    bool usable = true, any_at_or_below = false, all_below = true;
};

NodeAtSamples node_at_samples(const WalkEntry& e, std::span<const ReconstructionSample* const> samples,
                              size_t K) {
    NodeAtSamples n;
    for (size_t k = 0; k < K; ++k) {
        const SampleRef& ref = e.refs[k];
        n.imp[k] = &samples[k]->nodes[size_t(ref.slot)].impostor;
        n.gamma[k] = n.imp[k]->gamma * ref.scale;
        const double g = max_channel(n.gamma[k]);
        n.hi = k == 0 ? n.gamma[k] : glm::max(n.hi, n.gamma[k]);
        n.lo = k == 0 ? n.gamma[k] : glm::min(n.lo, n.gamma[k]);
        n.gamma_max = k == 0 ? g : std::max(n.gamma_max, g);
        n.gamma_min = k == 0 ? g : std::min(n.gamma_min, g);
        n.usable = n.usable && n.imp[k]->usable;
        n.any_at_or_below = n.any_at_or_below || ref.below || n.imp[k]->on_cut;
        n.all_below = n.all_below && ref.below;
        // The threshold's scale: the smallest total among samples that saw
        // light (the paper takes the smallest of all; a sample in full shadow
        // would make every threshold 0 and send the walk down to every leaf).
        const double G = n.imp[k]->Gamma;
        if (G > 0.0 && (n.smallest_total == 0.0 || G < n.smallest_total)) n.smallest_total = G;
    }
    return n;
}

// One point's walk down the tree, guided by the samples' cuts.
class ReconstructionWalk {
public:
    ReconstructionWalk(const WalkTree& tree, const SurfacePoint& p,
                       std::span<const ReconstructionSample* const> samples, std::span<const double> weights,
                       size_t K, double error_ratio, ShadowRayCount& rays)
        : tree_(tree),
          p_(p),
          open_(without_occluders(p)),
          glossy_(shading::has_lobe(p.specular, p.exponent)),
          samples_(samples),
          weights_(weights),
          K_(K),
          error_ratio_(error_ratio),
          rays_(rays) {
        for (size_t k = 0; k < K; ++k) total_here_ += weights[k] * max_channel(samples[k]->radiance);
    }

    glm::dvec3 run() {
        thread_local std::vector<WalkEntry> stack;
        stack.assign(1, WalkEntry{});
        while (!stack.empty()) {
            const WalkEntry e = stack.back();
            stack.pop_back();
            visit(e, stack);
        }
        return radiance_;
    }

private:
    void visit(const WalkEntry& e, std::vector<WalkEntry>& stack) {
        const GpuTreeNode& node = tree_.node(e.node);
        int32_t children[2];
        const int child_count = children_of(tree_, e.node, children);
        const bool leaf = child_count == 0;
        const NodeAtSamples n = node_at_samples(e, samples_, K_);
        const double spread = max_channel(n.hi - n.lo);
        const double tau = error_ratio_ * n.smallest_total;
        const bool junction = joins_types(node) && !leaf;

        // 1. Discard: dark at every sample.
        if (!junction && n.usable && n.gamma_max <= 0.0) return;
        // 2. Interpolate an impostor, unless no sample's cut reached this deep
        // or its direction lies in a glossy lobe.
        if (!junction && n.usable && !n.all_below && n.gamma_min > 0.0 && spread < tau && interpolate(n)) return;
        // 3. Evaluate the cluster as a lightcut would: a leaf, or a node small
        // against the threshold that some sample's cut reached.
        if (leaf) {
            radiance_ += evaluate_cluster(tree_, e.node, p_, open_, rays_);
            return;
        }
        if (!junction && n.any_at_or_below && evaluates(e.node, n, tau) && evaluate(e.node, n, tau)) return;
        // 4. Refine.
        for (int c = child_count - 1; c >= 0; --c) stack.push_back(child_entry(e, n, node, children[c], c));
    }

    // Adds the samples' interpolated impostor; false where it falls in the glossy lobe.
    bool interpolate(const NodeAtSamples& n) {
        glm::dvec3 d(0.0), g(0.0);
        for (size_t k = 0; k < K_; ++k) {
            d += weights_[k] * n.imp[k]->direction;
            g += weights_[k] * n.gamma[k];
        }
        if (!(glm::length(d) > 0.0)) return false;
        d = glm::normalize(d);
        const glm::dvec3 f = material_response(p_, d);
        if (inside_gloss_lobe(p_, f)) return false;
        radiance_ += f * std::max(glm::dot(p_.normal, d), 0.0) * g;
        return true;
    }

    // On a glossy point the samples' magnitudes (seen from other views) do not
    // bound a node inside this view's lobe: the node must also pass the
    // lightcut's own test here, its bound against the error ratio times the
    // samples' interpolated total; that test alone decides for a node the
    // samples' lobes could not see.
    bool evaluates(int32_t node, const NodeAtSamples& n, double tau) const {
        const bool small_at_samples = n.usable && n.gamma_max < tau;
        if (!glossy_) return small_at_samples;
        return (small_at_samples || !n.usable) &&
               max_channel(node_contribution_bound(tree_, node, p_)) <= error_ratio_ * total_here_;
    }

    // Adds the cluster's evaluation, unless it is far brighter here than any
    // sample predicts (its representative close to this point): then it is
    // refined instead, as the paper does.
    bool evaluate(int32_t node, const NodeAtSamples& n, double tau) {
        // What the samples predict here, and at least the threshold.
        double expected = 0.0;
        for (size_t k = 0; k < K_; ++k) {
            const glm::dvec3 M = material_term(p_, n.imp[k]->direction);
            expected = std::max({expected, max_channel(M * n.gamma[k]), max_channel(M) * tau});
        }
        const glm::dvec3 evaluated = evaluate_cluster(tree_, node, p_, open_, rays_);
        if (max_channel(evaluated) > kMuchBrighter * expected) return false;
        radiance_ += evaluated;
        return true;
    }

    WalkEntry child_entry(const WalkEntry& e, const NodeAtSamples& n, const GpuTreeNode& node,
                          int32_t child_node, int c) const {
        WalkEntry child;
        child.node = child_node;
        const double ratio = intensity_ratio(tree_.node(child_node), node);
        for (size_t k = 0; k < K_; ++k) {
            const SampleRef& ref = e.refs[k];
            const int32_t slot =
                ref.below || n.imp[k]->on_cut ? kBelowCut : samples_[k]->nodes[size_t(ref.slot)].children[c];
            child.refs[k] = slot != kBelowCut ? SampleRef{slot, 1.0, false}
                                              : SampleRef{ref.slot, ref.scale * ratio, true};
        }
        return child;
    }

    const WalkTree& tree_;
    const SurfacePoint& p_;
    const SurfacePoint open_;
    const bool glossy_;
    std::span<const ReconstructionSample* const> samples_;
    std::span<const double> weights_;
    const size_t K_;
    const double error_ratio_;
    ShadowRayCount& rays_;
    double total_here_ = 0.0;
    glm::dvec3 radiance_{0.0};
};

}  // namespace

glm::dvec3 reconstruction_cut(const WalkTree& tree, const SurfacePoint& p,
                              std::span<const ReconstructionSample* const> samples,
                              std::span<const double> weights, double error_ratio, ShadowRayCount& rays) {
    const size_t K = std::min(samples.size(), size_t(kMaxReconstructionSamples));
    if (tree.empty() || K == 0) return glm::dvec3(0.0);
    for (size_t k = 0; k < K; ++k) {
        if (samples[k]->nodes.empty()) return glm::dvec3(0.0);
    }
    return ReconstructionWalk(tree, p, samples, weights, K, error_ratio, rays).run();
}

}  // namespace lc

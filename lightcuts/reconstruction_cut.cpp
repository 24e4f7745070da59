#include "lightcuts/reconstruction_cut.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <numbers>
#include <utility>
#include <vector>

#include "lightcuts/cut_traversal.h"

namespace lc {
namespace {

// Unit direction from x towards a node's representative.
glm::dvec3 direction_to(const LightTreeNode& node, const glm::dvec3& x) {
    if (node.type == LightType::kDirectional) return -glm::normalize(glm::dvec3(node.direction));
    const glm::dvec3 to_light = glm::dvec3(node.position) - x;
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
// steel cabinet), so a direction where the lobe outweighs the diffuse term
// counts as inside too (measured: the cabinet's highlights were 50% off).
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
glm::dvec3 evaluate_cluster(const LightTreeNode& node, const SurfacePoint& p,
                            const SurfacePoint& open, ShadowRayCount& rays) {
    const glm::dvec3 unshadowed = shade_node(node, open);
    if (max_channel(unshadowed) <= 0.0) return glm::dvec3(0.0);
    if (p.occluders == nullptr) return unshadowed;
    ++rays.rays;
    return shade_node(node, p);
}

// The impostor of a node below a sample's cut: its ancestor's direction, the
// intensity scaled by the ratio of the clusters' intensities.
Impostor derived_impostor(const Impostor& ancestor, const LightTreeNode& parent,
                          const LightTreeNode& child) {
    Impostor imp = ancestor;
    const double parent_intensity = max_channel(glm::dvec3(parent.intensity));
    const double ratio =
        parent_intensity > 0.0 ? max_channel(glm::dvec3(child.intensity)) / parent_intensity : 0.0;
    imp.gamma *= ratio;
    imp.on_cut = false;
    imp.below_cut = true;
    return imp;
}

struct WalkEntry {
    int32_t node = 0;
    std::array<Impostor, kMaxReconstructionSamples> impostors;
};

}  // namespace

CutResult counted_lightcut(const LightTree& tree, const SurfacePoint& p, const CutSettings& settings,
                           ShadowRayCount& rays, std::vector<CutNodeEstimate>* nodes) {
    if (tree.empty()) return {};
    std::vector<CutNodeEstimate> cut;
    const CutResult result = bound_heap_cut(tree, p, settings, &cut);
    if (p.occluders != nullptr) {
        const SurfacePoint open = without_occluders(p);
        for (const CutNodeEstimate& entry : cut) {
            if (max_channel(shade_node(tree.nodes[size_t(entry.node)], open)) > 0.0) ++rays.rays;
        }
    }
    if (nodes != nullptr) *nodes = std::move(cut);
    return result;
}

ReconstructionSample make_reconstruction_sample(const LightTree& tree, const SurfacePoint& p,
                                                const CutSettings& settings,
                                                ShadowRayCount& rays) {
    ReconstructionSample sample;
    sample.point = p;
    if (tree.empty()) return sample;
    std::vector<CutNodeEstimate> cut;
    const CutResult result = counted_lightcut(tree, p, settings, rays, &cut);
    sample.radiance = result.radiance;
    sample.cut_size = result.cut_size;

    // Estimates and directions of the cut's nodes, then of every node above
    // them: the sum of the children's estimates, and their directions
    // weighted by those estimates (post-order, an explicit stack).
    std::unordered_map<int32_t, std::pair<glm::dvec3, glm::dvec3>> estimates;  // L, d
    estimates.reserve(cut.size() * 2);
    for (const CutNodeEstimate& entry : cut) {
        estimates[entry.node] = {entry.estimate,
                                 direction_to(tree.nodes[size_t(entry.node)], p.position)};
    }
    std::vector<std::pair<int32_t, bool>> stack{{0, false}};
    while (!stack.empty()) {
        auto [index, children_done] = stack.back();
        stack.pop_back();
        if (estimates.contains(index) && !children_done) continue;
        int32_t children[2];
        const int child_count = valid_children(tree, index, children);
        if (!children_done) {
            stack.push_back({index, true});
            for (int c = 0; c < child_count; ++c) stack.push_back({children[c], false});
            continue;
        }
        glm::dvec3 L(0.0), weighted(0.0), plain(0.0);
        for (int c = 0; c < child_count; ++c) {
            const auto& [child_L, child_d] = estimates[children[c]];
            L += child_L;
            weighted += max_channel(child_L) * child_d;
            plain += child_d;
        }
        const glm::dvec3 d = glm::length(weighted) > 0.0 ? weighted : plain;
        estimates[index] = {L, glm::length(d) > 0.0 ? glm::normalize(d) : p.normal};
    }
    std::unordered_map<int32_t, bool> on_cut;
    for (const CutNodeEstimate& entry : cut) on_cut[entry.node] = true;
    sample.impostors.reserve(estimates.size());
    for (const auto& [index, estimate] : estimates) {
        Impostor imp = make_impostor(p, estimate.second, estimate.first, result.radiance);
        imp.on_cut = on_cut.contains(index);
        sample.impostors[index] = imp;
    }
    return sample;
}

glm::dvec3 reconstruction_cut(const LightTree& tree, const SurfacePoint& p,
                              std::span<const ReconstructionSample* const> samples,
                              std::span<const double> weights, double error_ratio,
                              ShadowRayCount& rays) {
    const size_t K = std::min(samples.size(), size_t(kMaxReconstructionSamples));
    glm::dvec3 radiance(0.0);
    if (tree.empty() || K == 0) return radiance;
    const SurfacePoint open = without_occluders(p);
    // The threshold's scale: the smallest total among samples that saw light
    // (the paper takes the smallest of all; a sample in full shadow would
    // make every threshold 0 and send the walk down to every leaf).
    auto threshold = [&](const WalkEntry& e) {
        double smallest = 0.0;
        for (size_t k = 0; k < K; ++k) {
            const double G = e.impostors[k].Gamma;
            if (G > 0.0 && (smallest == 0.0 || G < smallest)) smallest = G;
        }
        return error_ratio * smallest;
    };

    std::vector<WalkEntry> stack(1);
    for (size_t k = 0; k < K; ++k) {
        auto it = samples[k]->impostors.find(0);
        if (it != samples[k]->impostors.end()) stack[0].impostors[k] = it->second;
    }
    while (!stack.empty()) {
        const WalkEntry e = stack.back();
        stack.pop_back();
        const LightTreeNode& node = tree.nodes[size_t(e.node)];
        int32_t children[2];
        const int child_count = valid_children(tree, e.node, children);
        const bool leaf = child_count == 0;

        double gamma_max = 0.0, gamma_min = 0.0, spread = 0.0;
        bool usable = true, any_at_or_below = false, all_below = true;
        for (int c = 0; c < 3; ++c) {
            double hi = e.impostors[0].gamma[c], lo = hi;
            for (size_t k = 1; k < K; ++k) {
                hi = std::max(hi, e.impostors[k].gamma[c]);
                lo = std::min(lo, e.impostors[k].gamma[c]);
            }
            spread = std::max(spread, hi - lo);
        }
        for (size_t k = 0; k < K; ++k) {
            const Impostor& imp = e.impostors[k];
            const double g = max_channel(imp.gamma);
            gamma_max = k == 0 ? g : std::max(gamma_max, g);
            gamma_min = k == 0 ? g : std::min(gamma_min, g);
            usable = usable && imp.usable;
            any_at_or_below = any_at_or_below || imp.on_cut || imp.below_cut;
            all_below = all_below && imp.below_cut;
        }
        const double tau = threshold(e);
        const bool junction = node.mixed_types && !leaf;

        // 1. Discard: dark at every sample.
        if (!junction && usable && gamma_max <= 0.0) continue;
        // 2. Interpolate an impostor, unless no sample's cut reached this deep
        // or its direction lies in a glossy lobe.
        if (!junction && usable && !all_below && gamma_min > 0.0 && spread < tau) {
            glm::dvec3 d(0.0), gamma(0.0);
            for (size_t k = 0; k < K; ++k) {
                d += weights[k] * e.impostors[k].direction;
                gamma += weights[k] * e.impostors[k].gamma;
            }
            if (glm::length(d) > 0.0) {
                d = glm::normalize(d);
                const glm::dvec3 f = material_response(p, d);
                if (!inside_gloss_lobe(p, f)) {
                    radiance += f * std::max(glm::dot(p.normal, d), 0.0) * gamma;
                    continue;
                }
            }
        }
        // 3. Evaluate the cluster as a lightcut would: a leaf, or a node small
        // against the threshold that some sample's cut reached.
        if (leaf || (!junction && usable && any_at_or_below && gamma_max < tau)) {
            radiance += evaluate_cluster(node, p, open, rays);
            continue;
        }
        // 4. Refine.
        for (int c = child_count - 1; c >= 0; --c) {
            WalkEntry child;
            child.node = children[c];
            const LightTreeNode& child_node = tree.nodes[size_t(children[c])];
            for (size_t k = 0; k < K; ++k) {
                const Impostor& parent = e.impostors[k];
                auto it = parent.on_cut || parent.below_cut
                              ? samples[k]->impostors.end()
                              : samples[k]->impostors.find(children[c]);
                child.impostors[k] = it != samples[k]->impostors.end()
                                         ? it->second
                                         : derived_impostor(parent, node, child_node);
            }
            stack.push_back(child);
        }
    }
    return radiance;
}

}  // namespace lc

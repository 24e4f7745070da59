// The lightcut's error at chosen pixels, node by node, against the exact sum
// (CPU evaluator, double precision, the shaders' formulas and shadow rays):
// which cut nodes carry the error, whether their representative is hidden
// while most of their light is visible, whether any bound lies below the
// cluster's true contribution, and what the same cut gives when every node's
// representative is drawn again in proportion to intensity (the paper's
// random choice; the tree fixes one draw for the whole image). Also checks
// the tree's draws: each junction's representative is its first child's with
// probability I_first / I (a z-score over the junctions).
//
//   cut_error_audit_bench SCENE.gltf TREE.lcut WxH E MAX_CUT PIXELS.txt OUT.csv [STRIDE]
//
// PIXELS.txt holds "x y" per line; STRIDE > 1 places the eye rays as
// `render --pixel-stride` does. The cut is the walk search's (bound_walk.h);
// the CSV also has the heap search's estimate. A diagnostic for
// docs/BENCHMARKS.md ("Accuracy at E = 0.005"), not run by any script.
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <utility>
#include <vector>

#include "editor_client/render/gbuffer_surface.h"
#include "editor_client/render/pixel_stride.h"
#include "editor_client/render/render_inputs.h"
#include "editor_client/render/renderer.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/vk/context.h"
#include "lightcuts/cuts/bound_walk.h"
#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/seeded_mixer.h"
#include "tests/benchmarks/gbuffer_diagnostic.h"

namespace lc::client {
namespace {

// Redraws of the representatives per pixel.
constexpr int kRedraws = 400;
// The accuracy target's tolerance: a pixel within 2% of the reference.
constexpr double kTolerance = 0.02;

double luminance(const glm::dvec3& v) { return 0.2126 * v.x + 0.7152 * v.y + 0.0722 * v.z; }

std::vector<int32_t> leaves_under(const WalkTree& tree, int32_t index) {
    std::vector<int32_t> leaves;
    std::vector<int32_t> stack{index};
    while (!stack.empty()) {
        const int32_t i = stack.back();
        stack.pop_back();
        int32_t children[2];
        const int count = children_of(tree, i, children);
        if (count == 0) leaves.push_back(i);
        for (int c = 0; c < count; ++c) stack.push_back(children[c]);
    }
    return leaves;
}

// z-score of the junctions' draws: 0 on average when each takes its first
// child's representative with probability I_first / I.
double representative_draw_z(const WalkTree& tree) {
    double z = 0.0, junctions = 0.0;
    for (size_t i = 0; i < tree.nodes.size(); ++i) {
        int32_t children[2];
        if (children_of(tree, int32_t(i), children) != 2) continue;
        const GpuTreeNode& first = tree.node(children[0]);
        const double I_first = luminance(glm::dvec3(first.intensity));
        const double I = I_first + luminance(glm::dvec3(tree.node(children[1]).intensity));
        const double p = I_first / I;
        if (!(p > 0.0 && p < 1.0)) continue;
        const double took_first = tree.nodes[i].representative == first.representative ? 1.0 : 0.0;
        z += (took_first - p) / std::sqrt(p * (1.0 - p));
        junctions += 1.0;
    }
    return junctions > 0.0 ? z / std::sqrt(junctions) : 0.0;
}

struct PixelAudit {
    int x = 0, y = 0;
    double exact = 0.0;            // every leaf with its shadow ray
    double unshadowed = 0.0;       // every leaf, V = 1
    double walk = 0.0, heap = 0.0;  // the two searches' estimates
    uint32_t walk_size = 0;
    bool walk_max_cut = false;
    double error_hidden_rep = 0.0;   // summed over nodes whose representative is hidden
    double error_visible_rep = 0.0;  // over the others
    int hidden_rep_mostly_visible = 0;  // nodes hidden from p by their representative alone
    double sigma = 0.0;  // the random draw's standard deviation of the cut's estimate
    double worst_node_error = 0.0;
    double worst_node_visible = 0.0;  // that node's visible share of its unshadowed light
    int bound_violations = 0;         // nodes whose bound is below their error or light
    double p_dark = 0.0, p_bright = 0.0;  // the redraws' shares beyond kTolerance
};

// One cut node's leaves: the cumulative intensity share and the estimate the
// node would give with that leaf as its representative.
using Draws = std::vector<std::pair<double, double>>;

PixelAudit audit_pixel(const WalkTree& tree, const SurfacePoint& shadowed, const CutSettings& settings,
                       uint64_t seed) {
    SurfacePoint open = shadowed;
    open.occluders = nullptr;
    PixelAudit a;
    a.exact = luminance(shade_tree_leaves(tree, shadowed));
    a.unshadowed = luminance(shade_tree_leaves(tree, open));
    CutSettings heap = settings;
    heap.search = BoundSearch::kHeap;
    a.heap = luminance(bound_heap_cut(tree, shadowed, heap).radiance);
    std::vector<CutNodeEstimate> nodes;
    const CutResult walk = bound_walk_cut(tree, shadowed, settings, &nodes);
    a.walk = luminance(walk.radiance);
    a.walk_size = walk.cut_size;
    a.walk_max_cut = walk.max_cut_hit;

    std::vector<Draws> draws;
    double variance = 0.0;
    for (const CutNodeEstimate& n : nodes) {
        const GpuTreeNode& node = tree.node(n.node);
        const double I_C = luminance(glm::dvec3(node.intensity));
        double exact = 0.0, light = 0.0, visible_light = 0.0, I_sum = 0.0;
        Draws cdf;
        for (int32_t leaf_index : leaves_under(tree, n.node)) {
            const double v = luminance(shade_node(tree, leaf_index, shadowed));
            const double u = luminance(shade_node(tree, leaf_index, open));
            const double I = luminance(glm::dvec3(tree.node(leaf_index).intensity));
            exact += v;
            light += u;
            if (v > 0.0) visible_light += u;
            I_sum += I;
            cdf.push_back({I_sum, I > 0.0 ? I_C * v / I : 0.0});
        }
        for (auto& [cumulative, estimate] : cdf) cumulative /= I_sum;
        double previous = 0.0;
        for (const auto& [cumulative, estimate] : cdf) {
            variance += (cumulative - previous) * (estimate - exact) * (estimate - exact);
            previous = cumulative;
        }
        draws.push_back(std::move(cdf));

        const double estimate = luminance(n.estimate);
        const double error = estimate - exact;
        const double visible = light > 0.0 ? visible_light / light : 1.0;
        const bool hidden = estimate == 0.0 && luminance(shade_node(tree, n.node, open)) > 0.0;
        (hidden ? a.error_hidden_rep : a.error_visible_rep) += error;
        if (hidden && visible > 0.5) ++a.hidden_rep_mostly_visible;
        if (std::abs(error) > std::abs(a.worst_node_error)) {
            a.worst_node_error = error;
            a.worst_node_visible = visible;
        }
        if (!is_leaf(node)) {
            const glm::dvec3 b = node_contribution_bound(tree, n.node, shadowed);
            const double bound = std::max({b.x, b.y, b.z}) * (1.0 + 1e-9);
            if (light > bound || std::abs(error) > bound) ++a.bound_violations;
        }
    }
    a.sigma = std::sqrt(variance);

    SplitMix64 rng(seed);
    int dark = 0, bright = 0;
    for (int d = 0; d < kRedraws; ++d) {
        double total = 0.0;
        for (const Draws& cdf : draws) {
            const double u = rng.uniform();
            auto it = std::lower_bound(cdf.begin(), cdf.end(), u,
                                       [](const std::pair<double, double>& e, double v) { return e.first < v; });
            total += (it == cdf.end() ? cdf.back() : *it).second;
        }
        const double relative = (total - a.exact) / a.exact;
        dark += relative < -kTolerance;
        bright += relative > kTolerance;
    }
    a.p_dark = double(dark) / kRedraws;
    a.p_bright = double(bright) / kRedraws;
    return a;
}

int run(int argc, char** argv) {
    if (argc < 8) {
        std::fprintf(stderr, "usage: %s SCENE TREE WxH E MAX_CUT PIXELS OUT [STRIDE]\n", argv[0]);
        return 2;
    }
    GBufferDiagnostic d = load_diagnostic(argv[1], argv[2]);
    const WalkTree& tree = d.walk;
    std::fprintf(stderr, "representative draws: z = %.2f over the junctions\n",
                 representative_draw_z(tree));

    RenderSettings settings = diagnostic_settings(d, argv[3]);
    if (argc > 8) settings = or_exit(strided_settings(settings, uint32_t(std::atoi(argv[8]))));
    CutSettings cut;
    cut.criterion = CutCriterion::kBound;
    cut.error_ratio = std::atof(argv[4]);
    cut.max_cut = uint32_t(std::atoi(argv[5]));

    draw_gbuffer(d, settings);

    std::vector<std::pair<int, int>> pixels;
    std::ifstream in(argv[6]);
    for (int x, y; in >> x >> y;) pixels.push_back({x, y});
    std::vector<PixelAudit> audits(pixels.size());
    for_each_index(pixels.size(), [&](size_t k) {
        const auto [x, y] = pixels[k];
        const SurfacePoint p = diagnostic_point(d, settings.width, x, y);
        audits[k] = audit_pixel(tree, p, cut, mix64(k + 1));
        audits[k].x = x;
        audits[k].y = y;
    });

    std::FILE* out = std::fopen(argv[7], "w");
    if (out == nullptr) return 1;
    std::fprintf(out,
                 "x,y,exact,unshadowed,walk,heap,walk_size,walk_max_cut,error_hidden_rep,"
                 "error_visible_rep,hidden_rep_mostly_visible,sigma,worst_node_error,"
                 "worst_node_visible,bound_violations,p_dark,p_bright\n");
    for (const PixelAudit& a : audits)
        std::fprintf(out, "%d,%d,%.9g,%.9g,%.9g,%.9g,%u,%d,%.9g,%.9g,%d,%.9g,%.9g,%.4f,%d,%.4f,%.4f\n",
                     a.x, a.y, a.exact, a.unshadowed, a.walk, a.heap, a.walk_size, int(a.walk_max_cut),
                     a.error_hidden_rep, a.error_visible_rep, a.hidden_rep_mostly_visible, a.sigma,
                     a.worst_node_error, a.worst_node_visible, a.bound_violations, a.p_dark, a.p_bright);
    std::fclose(out);
    return 0;
}

}  // namespace
}  // namespace lc::client

int main(int argc, char** argv) { return lc::client::run(argc, argv); }

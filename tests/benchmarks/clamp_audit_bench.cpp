// The automatic clamp of indirect light at a grid of pixels (CPU evaluator,
// double precision, shadow rays): the cut's two-largest approximation against
// the exact clamp of the same cut's nodes, and the exact reference of every
// leaf, with its threshold. Answers two questions of issue 16: how far the
// cut's approximation is from the exact clamp of its own lights, and how
// many pixels the exact reference leaves without indirect light (a zero
// threshold: fewer comparable VPLs than 1 / ratio and no other light) where
// the lightcut keeps it.
//
//   clamp_audit_bench SCENE.gltf TREE.lcut WxH E GRID OUT.csv
//
// GRID: every GRID-th pixel in x and y. A diagnostic for docs/ACCURACY.md
// ("The exact clamp in the reference"), not run by any script.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <vector>

#include "editor_client/render/gbuffer_surface.h"
#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/cuts/exact_indirect_clamp.h"
#include "tests/benchmarks/gbuffer_diagnostic.h"

namespace lc::client {
namespace {

double sum_of(const glm::dvec3& v) { return v.x + v.y + v.z; }

struct PixelClamp {
    int x = 0, y = 0;
    double cut = 0.0;             // the cut, its VPLs clamped by the approximation
    double cut_exact = 0.0;       // the same cut's nodes, its VPLs clamped exactly
    double cut_buckets = 0.0;     // the same cut, clamped by the bucket candidate
    double cut_vpls = 0.0;        // the cut's VPL leaves before the clamp
    double cut_others = 0.0;      // the rest of the cut (direct light, indirect clusters)
    double reference = 0.0;       // every leaf, its VPLs clamped exactly
    double reference_vpls = 0.0;  // every VPL before the clamp
    double reference_others = 0.0;
    double threshold = 0.0;       // the reference's, largest channel
    uint32_t vpls_lighting = 0;   // VPLs that reach the pixel
};

// A candidate for the cut's clamp (not in the product: on llvmpipe the
// shaders' buckets made lightcuts 3-4x slower): per channel, the lights
// under the two largest in 8 buckets a factor of 2 apart below the largest
// (sum and count), each bucket's sum of min(L, t) along the chord between
// its ends, the last one's as min(sum, count x t).
double channel_bucketed_clamp(const glm::dvec3& others, const std::vector<glm::dvec3>& leaves, double ratio,
                              int buckets) {
    double total = 0.0;
    for (int c = 0; c < 3; ++c) {
        std::vector<double> v;
        for (const glm::dvec3& l : leaves) v.push_back(l[c]);
        std::sort(v.begin(), v.end(), std::greater<>());
        const double a = v.size() > 0 ? v[0] : 0.0, b = v.size() > 1 ? v[1] : 0.0;
        std::vector<double> sums(size_t(buckets), 0.0), counts(size_t(buckets), 0.0), upper(size_t(buckets), 0.0);
        if (v.size() > 2 && v[2] > 0.0) {
            const int top = std::ilogb(v[2]) + 1;
            for (int j = 0; j < buckets; ++j) upper[size_t(j)] = std::ldexp(1.0, top - j);
            for (size_t i = 2; i < v.size(); ++i) {
                int j = v[i] > 0.0 ? top - (std::ilogb(v[i]) + 1) : buckets - 1;
                j = std::clamp(j, 0, buckets - 1);
                sums[size_t(j)] += v[i];
                counts[size_t(j)] += 1.0;
            }
        }
        const auto g = [&](double t) {
            double r = others[c] + std::min(a, t) + std::min(b, t);
            for (size_t j = 0; j < sums.size(); ++j) {
                const double u = upper[j];
                if (counts[j] == 0.0) continue;
                if (t >= u || j + 1 == sums.size()) {
                    r += std::min(sums[j], counts[j] * t);
                } else if (t <= 0.5 * u) {
                    r += counts[j] * t;
                } else {
                    const double low = counts[j] * 0.5 * u;
                    r += low + (sums[j] - low) * (t - 0.5 * u) / (0.5 * u);
                }
            }
            return r;
        };
        double lo = 0.0, hi = g(1e300) * ratio;
        for (int i = 0; i < 200; ++i) {
            const double mid = 0.5 * (lo + hi);
            (ratio * g(mid) > mid ? lo : hi) = mid;
        }
        total += g(lo);
    }
    return total;
}

PixelClamp audit_pixel(const WalkTree& tree, const SurfacePoint& p, const CutSettings& settings) {
    PixelClamp a;
    const double ratio = indirect_clamp_ratio(settings.error_ratio);
    std::vector<CutNodeEstimate> nodes;
    a.cut = sum_of(bound_heap_cut(tree, p, settings, &nodes).radiance);
    glm::dvec3 others(0.0);
    std::vector<glm::dvec3> leaves;
    for (const CutNodeEstimate& n : nodes) {
        const GpuTreeNode& node = tree.node(n.node);
        if (is_indirect(node) && !is_patch(node) && is_leaf(node)) {
            leaves.push_back(n.estimate);
        } else {
            others += n.estimate;
        }
    }
    a.cut_exact = sum_of(exact_indirect_clamp(others, leaves, ratio).radiance);
    a.cut_buckets = channel_bucketed_clamp(others, leaves, ratio, 8);
    for (const glm::dvec3& l : leaves) a.cut_vpls += sum_of(l);
    a.cut_others = sum_of(others);

    others = glm::dvec3(0.0);
    leaves.clear();
    for (const GpuLight& light : tree.leaves) {
        const glm::dvec3 c = shade_light(light, p);
        if (is_indirect(light) && !is_patch(light)) {
            leaves.push_back(c);
            a.vpls_lighting += sum_of(c) > 0.0;
        } else {
            others += c;
        }
    }
    const ExactClamp exact = exact_indirect_clamp(others, leaves, ratio);
    a.reference = sum_of(exact.radiance);
    for (const glm::dvec3& l : leaves) a.reference_vpls += sum_of(l);
    a.reference_others = sum_of(others);
    a.threshold = std::max({exact.threshold.x, exact.threshold.y, exact.threshold.z});
    return a;
}

int run(int argc, char** argv) {
    if (argc < 7) {
        std::fprintf(stderr, "usage: %s SCENE TREE WxH E GRID OUT\n", argv[0]);
        return 2;
    }
    GBufferDiagnostic d = load_diagnostic(argv[1], argv[2]);
    RenderSettings settings = diagnostic_settings(d, argv[3]);
    CutSettings cut;
    cut.criterion = CutCriterion::kBound;
    cut.search = BoundSearch::kHeap;
    cut.error_ratio = std::atof(argv[4]);
    const int grid = std::max(1, std::atoi(argv[5]));

    draw_gbuffer(d, settings);
    const GBufferReadback& g = d.gbuffer;

    std::vector<std::pair<int, int>> pixels;
    for (uint32_t y = uint32_t(grid / 2); y < settings.height; y += uint32_t(grid))
        for (uint32_t x = uint32_t(grid / 2); x < settings.width; x += uint32_t(grid))
            if (g.position[4 * (size_t(y) * settings.width + x) + 3] != 0.0f) pixels.push_back({int(x), int(y)});
    std::vector<PixelClamp> audits(pixels.size());
    for_each_index(pixels.size(), [&](size_t k) {
        const auto [x, y] = pixels[k];
        const SurfacePoint p = diagnostic_point(d, settings.width, x, y);
        audits[k] = audit_pixel(d.walk, p, cut);
        audits[k].x = x;
        audits[k].y = y;
    });

    std::FILE* out = std::fopen(argv[6], "w");
    if (out == nullptr) return 1;
    std::fprintf(out,
                 "x,y,cut,cut_exact,cut_buckets,cut_vpls,cut_others,reference,reference_vpls,reference_others,threshold,"
                 "vpls_lighting\n");
    for (const PixelClamp& a : audits)
        std::fprintf(out, "%d,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%u\n", a.x, a.y, a.cut, a.cut_exact,
                     a.cut_buckets,
                     a.cut_vpls, a.cut_others, a.reference, a.reference_vpls, a.reference_others, a.threshold,
                     a.vpls_lighting);
    std::fclose(out);
    return 0;
}

}  // namespace
}  // namespace lc::client

int main(int argc, char** argv) { return lc::client::run(argc, argv); }

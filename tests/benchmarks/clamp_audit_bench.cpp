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
#include <atomic>
#include <cmath>
#include <functional>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <thread>
#include <vector>

#include "editor_client/render/gbuffer_surface.h"
#include "editor_client/scene/gltf_loader.h"
#include "editor_client/render/render_inputs.h"
#include "editor_client/render/renderer.h"
#include "editor_client/vk/context.h"
#include "lightcuts/cpu_evaluator.h"
#include "lightcuts/exact_indirect_clamp.h"

namespace lc::client {
namespace {

template <typename T>
T or_exit(Result<T> r) {
    if (!r) {
        std::cerr << r.error() << "\n";
        std::exit(1);
    }
    return std::move(r).value();
}

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

PixelClamp audit_pixel(const LightTree& tree, const SurfacePoint& p, const CutSettings& settings) {
    PixelClamp a;
    const double ratio = indirect_clamp_ratio(settings.error_ratio);
    std::vector<CutNodeEstimate> nodes;
    a.cut = sum_of(bound_heap_cut(tree, p, settings, &nodes).radiance);
    glm::dvec3 others(0.0);
    std::vector<glm::dvec3> leaves;
    for (const CutNodeEstimate& n : nodes) {
        const LightTreeNode& node = tree.nodes[size_t(n.node)];
        if (node.indirect && !node.patch && node.is_leaf()) {
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
    for (const LightTreeNode& node : tree.nodes) {
        if (!node.is_leaf()) continue;
        const glm::dvec3 c = shade_node(node, p);
        if (node.indirect && !node.patch) {
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
    const Scene scene = or_exit(load_scene(argv[1]));
    TreeSource source;
    source.dump = argv[2];
    const std::shared_ptr<const LightTree> tree = or_exit(obtain_tree(scene, source));
    RenderSettings settings;
    settings.mode = RenderMode::kLightcuts;
    settings.criterion = CutCriterion::kBound;
    if (std::sscanf(argv[3], "%ux%u", &settings.width, &settings.height) != 2) return 2;
    settings.camera = or_exit(choose_camera(scene, "", std::nullopt,
                                            float(settings.width) / float(settings.height)));
    CutSettings cut;
    cut.criterion = CutCriterion::kBound;
    cut.search = BoundSearch::kHeap;
    cut.error_ratio = std::atof(argv[4]);
    const int grid = std::max(1, std::atoi(argv[5]));

    vk::ContextOptions context_options;
    context_options.validation = false;
    const vk::Context context = or_exit(vk::Context::create(context_options));
    const std::unique_ptr<Renderer> renderer = or_exit(Renderer::create(context, scene, tree.get(), {}));
    if (Status drawn = renderer->render_gbuffer(settings); !drawn) {
        std::cerr << drawn.error() << "\n";
        return 1;
    }
    const GBufferReadback g = or_exit(renderer->read_gbuffer());

    std::vector<std::pair<int, int>> pixels;
    for (uint32_t y = uint32_t(grid / 2); y < settings.height; y += uint32_t(grid))
        for (uint32_t x = uint32_t(grid / 2); x < settings.width; x += uint32_t(grid))
            if (g.position[4 * (size_t(y) * settings.width + x) + 3] != 0.0f) pixels.push_back({int(x), int(y)});
    std::vector<PixelClamp> audits(pixels.size());
    std::atomic<size_t> next{0};
    const auto work = [&] {
        for (size_t k; (k = next.fetch_add(1)) < pixels.size();) {
            const auto [x, y] = pixels[k];
            SurfacePoint p = gbuffer_surface_point(g, size_t(y) * settings.width + size_t(x));
            p.occluders = &renderer->shadow_bvh();
            p.shadow_bias = renderer->shadow_bias();
            audits[k] = audit_pixel(*tree, p, cut);
            audits[k].x = x;
            audits[k].y = y;
        }
    };
    std::vector<std::thread> workers;
    for (unsigned t = 0; t < std::max(1u, std::thread::hardware_concurrency()); ++t) workers.emplace_back(work);
    for (std::thread& t : workers) t.join();

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

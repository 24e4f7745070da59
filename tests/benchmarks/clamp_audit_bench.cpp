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
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <thread>
#include <vector>

#include "editor_client/render/gbuffer_surface.h"
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
    double cut_vpls = 0.0;        // the cut's VPL leaves before the clamp
    double cut_others = 0.0;      // the rest of the cut (direct light, indirect clusters)
    double reference = 0.0;       // every leaf, its VPLs clamped exactly
    double reference_vpls = 0.0;  // every VPL before the clamp
    double reference_others = 0.0;
    double threshold = 0.0;       // the reference's, largest channel
    uint32_t vpls_lighting = 0;   // VPLs that reach the pixel
};

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
                 "x,y,cut,cut_exact,cut_vpls,cut_others,reference,reference_vpls,reference_others,threshold,"
                 "vpls_lighting\n");
    for (const PixelClamp& a : audits)
        std::fprintf(out, "%d,%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%u\n", a.x, a.y, a.cut, a.cut_exact,
                     a.cut_vpls, a.cut_others, a.reference, a.reference_vpls, a.reference_others, a.threshold,
                     a.vpls_lighting);
    std::fclose(out);
    return 0;
}

}  // namespace
}  // namespace lc::client

int main(int argc, char** argv) { return lc::client::run(argc, argv); }

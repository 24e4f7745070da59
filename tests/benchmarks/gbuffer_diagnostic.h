#pragma once
// What the CPU diagnostics over a rendered G-buffer share
// (cut_error_audit_bench, clamp_audit_bench): a scene and its tree dump
// loaded, the G-buffer drawn on the device with the scene's camera, and the
// pixels' work spread over the machine's threads. Any failure ends the program.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <memory>
#include <thread>
#include <vector>

#include "editor_client/render/gbuffer_surface.h"
#include "editor_client/render/render_inputs.h"
#include "editor_client/render/renderer.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/vk/context.h"
#include "lightcuts/tree/gpu_layout.h"

namespace lc::client {

template <typename T>
T or_exit(Result<T> r) {
    if (!r) {
        std::cerr << r.error() << "\n";
        std::exit(1);
    }
    return std::move(r).value();
}

struct GBufferDiagnostic {
    Scene scene;
    std::shared_ptr<const LightTree> tree;  // the import form, for the audits' tree census
    WalkTree walk;                          // what the renderer and the CPU evaluator walk
    std::unique_ptr<vk::Context> context;  // the renderer keeps a reference to it
    std::unique_ptr<Renderer> renderer;
    GBufferReadback gbuffer;
};

// The scene and its tree dump.
inline GBufferDiagnostic load_diagnostic(const char* scene_path, const char* tree_dump) {
    GBufferDiagnostic d;
    d.scene = or_exit(load_scene(scene_path));
    TreeSource source;
    source.dump = tree_dump;
    d.tree = or_exit(obtain_tree(d.scene, source));
    if (d.tree) d.walk = or_exit(make_walk_tree(*d.tree));
    return d;
}

// The scene's camera for an image of settings' size.
// The bound criterion's lightcuts at `size` ("WxH") through the scene's own camera.
inline RenderSettings diagnostic_settings(const GBufferDiagnostic& d, const char* size) {
    RenderSettings settings;
    settings.mode = RenderMode::kLightcuts;
    settings.criterion = CutCriterion::kBound;
    if (std::sscanf(size, "%ux%u", &settings.width, &settings.height) != 2 || settings.width == 0 ||
        settings.height == 0) {
        std::cerr << "size '" << size << "' is not WxH\n";
        std::exit(2);
    }
    settings.camera =
        or_exit(choose_camera(d.scene, "", std::nullopt, float(settings.width) / float(settings.height)));
    return settings;
}

// Draws the G-buffer of `settings` on the device and reads it back.
inline void draw_gbuffer(GBufferDiagnostic& d, const RenderSettings& settings) {
    vk::ContextOptions context_options;
    context_options.validation = false;
    d.context = std::make_unique<vk::Context>(or_exit(vk::Context::create(context_options)));
    d.renderer = or_exit(Renderer::create(*d.context, d.scene, d.tree ? &d.walk : nullptr, {}));
    if (Status drawn = d.renderer->render_gbuffer(settings); !drawn) {
        std::cerr << drawn.error() << "\n";
        std::exit(1);
    }
    d.gbuffer = or_exit(d.renderer->read_gbuffer());
}

// Pixel (x, y)'s surface point, with the renderer's occluders.
inline SurfacePoint diagnostic_point(const GBufferDiagnostic& d, uint32_t width, int x, int y) {
    SurfacePoint p = gbuffer_surface_point(d.gbuffer, size_t(y) * width + size_t(x));
    p.occluders = &d.renderer->shadow_bvh();
    p.shadow_bias = d.renderer->shadow_bias();
    return p;
}

// work(k) for k in [0, count), over the machine's threads.
inline void for_each_index(size_t count, const std::function<void(size_t)>& work) {
    std::atomic<size_t> next{0};
    std::vector<std::thread> workers;
    for (unsigned t = 0; t < std::max(1u, std::thread::hardware_concurrency()); ++t)
        workers.emplace_back([&] {
            for (size_t k; (k = next.fetch_add(1)) < count;) work(k);
        });
    for (std::thread& t : workers) t.join();
}

}  // namespace lc::client

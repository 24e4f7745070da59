#pragma once
// The interactive frame loop of `editor_client view`: input -> orbit camera
// and mode -> renderer -> blit into the swapchain -> present, one frame in
// flight. With a headless window the frames are rendered but not presented.
#include <cstdint>
#include <filesystem>

#include "editor_client/render/render_settings.h"
#include "editor_client/render/renderer.h"
#include "editor_client/vk/context.h"
#include "editor_client/window/window.h"
#include "lightcuts/result.h"

namespace lc::client {

struct ViewOptions {
    RenderSettings settings;           // the first frame's mode, size, camera and exposure
    uint32_t frames = 0;               // stop after this many frames; 0: until the window closes
    std::filesystem::path screenshot;  // when set, the last frame is saved as PNG
};

struct ViewSummary {
    uint32_t frames = 0;
    RenderSettings last_settings;
    double last_render_ms = 0.0;  // GPU time of the last frame
};

// `context` must have been created with the window's extensions and surface
// (ContextOptions::create_surface) when the window has one.
Result<ViewSummary> run_view_loop(Window& window, const vk::Context& context, Renderer& renderer,
                                  const ViewOptions& options);

}  // namespace lc::client

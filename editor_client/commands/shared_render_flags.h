#pragma once
// The flags `render` and `view` both take, registered by one function so a
// name, a range or a default is written once: the real-time mode's cut and
// shadow rays, the cluster representatives, shadows and the G-buffer's making.
#include <CLI/CLI.hpp>

#include <cstdint>

#include "editor_client/render/settings/render_settings.h"
#include "lightcuts/cuts/cpu_evaluator.h"
#include "lightcuts/occlusion/shadow_ray.h"

namespace lc::client {

struct SharedRenderFlags {
    uint32_t realtime_cut = 16;
    uint32_t realtime_rays = kDefaultRealtimeRays;
    Representatives representatives = Representatives::kTree;
    ShadowMode shadows = ShadowMode::kAuto;
    PrimaryChoice primary = PrimaryChoice::kAuto;
};

void add_shared_render_flags(CLI::App& cmd, SharedRenderFlags& flags);

}  // namespace lc::client

#pragma once
// One entry of the real-time sweep (--sweep-realtime): a mode, its settings
// and a label. Each kind of entry is one row of a table in
// realtime_variant.cpp, so that a new real-time mode is one more row there.
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "editor_client/render/settings/render_settings.h"
#include "lightcuts/result.h"

namespace lc::client {

struct RealtimeVariant {
    std::string label;  // "K16", "K8r1", "lc0.02": the table's and the CSV's name
    RenderMode mode = RenderMode::kRealtime;
    // Frames of a still view converge (false: every frame is the same image,
    // so one frame's error holds for every count and only its time adds up).
    bool accumulates = true;
    std::function<void(RenderSettings&)> configure;  // sets the mode's own settings
};

// The settings a variant renders with: `base` (size, camera, tree options) with the variant's mode and settings.
RenderSettings variant_settings(const RealtimeVariant& variant, const RenderSettings& base);

// "lc,K8r1,16,32": comma-separated items, at least one, labels distinct.
//   lc, lc0.05   deterministic lightcuts at E = `base.error_ratio` or the ratio given;
//   K16, K8r1    stochastic lightcuts (realtime) at K = 16, with `base.realtime_rays` or 1 ray a pixel;
//   restir, restir16  ReSTIR DI with `base.restir`, or with 16 candidates a pixel;
//   16           the same as K16 (the flag's older form, a list of cut sizes).
Result<std::vector<RealtimeVariant>> parse_realtime_variants(std::string_view text, const RenderSettings& base);

}  // namespace lc::client

#pragma once
// What the editor shows: mode, cut criterion and its controls, camera and
// exposure. Edited through EditorSession so every change is validated.
#include "editor_client/render/cpu_evaluator.h"
#include "editor_client/render/render_settings.h"

namespace lc::client {

// Bounds of the error-ratio control (the paper's default is 0.02).
inline constexpr double kMinErrorRatio = 1e-4;
inline constexpr double kMaxErrorRatio = 1.0;
inline constexpr uint32_t kMaxMaxCut = 1u << 16;

struct ViewState {
    RenderMode mode = RenderMode::kReference;
    CutCriterion criterion = CutCriterion::kRadius;
    double error_ratio = 0.02;
    uint32_t max_cut = kDefaultMaxCut;
    RenderCamera camera;
    float exposure = 1.0f;

    CutSettings cut_settings() const { return {criterion, error_ratio, max_cut}; }
};

}  // namespace lc::client

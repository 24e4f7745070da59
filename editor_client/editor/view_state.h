#pragma once
// What the editor shows: mode, cut criterion and its controls, camera and
// exposure. Edited through EditorSession so every change is validated.
#include "lightcuts/cuts/cpu_evaluator.h"
#include "editor_client/render/settings/render_settings.h"

namespace lc::client {

// Bounds of the error-ratio control (the paper's default is 0.02).
inline constexpr double kMinErrorRatio = 1e-4;
inline constexpr double kMaxErrorRatio = 1.0;
inline constexpr uint32_t kMaxMaxCut = kMaxGpuCut;  // what the renderer accepts

struct ViewState {
    RenderMode mode = RenderMode::kReference;
    CutCriterion criterion = CutCriterion::kBound;  // the paper's, as `render` defaults to
    double error_ratio = 0.02;
    uint32_t max_cut = kDefaultMaxCut;
    // Bound criterion: how a cluster is evaluated (render --representatives).
    Representatives representatives = Representatives::kTree;
    // Real-time mode: nodes of each block's cut (shadow rays per pixel and frame).
    uint32_t realtime_cut = 16;
    // Real-time mode: shadow rays per pixel and frame (0: one per cut node).
    uint32_t realtime_rays = kDefaultRealtimeRays;
    RestirSettings restir;  // the ReSTIR mode's options
    RenderCamera camera;
    float exposure = 1.0f;

    CutSettings cut_settings() const { return {criterion, error_ratio, max_cut}; }
};

// What the renderer is asked for at a size: every control of the view, with
// reference mode while there is no tree to cut.
inline RenderSettings render_settings_for(const ViewState& view, uint32_t width, uint32_t height,
                                          bool has_tree) {
    RenderSettings s;
    s.mode = view.mode;
    if (mode_needs_tree(s.mode) && !has_tree) s.mode = RenderMode::kReference;
    s.criterion = view.criterion;
    s.error_ratio = float(view.error_ratio);
    s.max_cut = view.max_cut;
    s.representatives = view.representatives;
    s.realtime_cut = view.realtime_cut;
    s.realtime_rays = view.realtime_rays;
    s.restir = view.restir;
    s.width = width;
    s.height = height;
    s.camera = view.camera;
    s.exposure = view.exposure;
    return s;
}

}  // namespace lc::client

#pragma once
// What the editor's view shows: mode, cut criterion and its settings, the
// real-time mode's cut and rays, camera, exposure. Every change is checked
// as the renderer would check it, and refused whole with the reason.
#include <cstdint>
#include <string_view>

#include "editor_client/editor/view_state.h"
#include "lightcuts/result.h"

namespace lc::client {

class ViewSettings {
public:
    explicit ViewSettings(const RenderCamera& camera) { view_.camera = camera; }

    const ViewState& state() const { return view_; }
    Status set_mode(std::string_view name);
    void set_mode(RenderMode mode) { view_.mode = mode; }
    Status set_criterion(std::string_view name);
    void set_criterion(CutCriterion criterion) { view_.criterion = criterion; }
    Status set_error_ratio(double ratio);
    Status set_max_cut(uint32_t max_cut);
    // The real-time mode's cut per block, 1 to 32 nodes (render --realtime-cut).
    Status set_realtime_cut(uint32_t nodes);
    // Its shadow rays per pixel and frame, 0 to 8; 0: one per cut node (render --realtime-rays).
    Status set_realtime_rays(uint32_t rays);
    // The ReSTIR mode's options (range-checked).
    Status set_restir(const RestirSettings& restir);
    // tree, pixel or importance (render --representatives); per-pixel draws need the bound criterion.
    Status set_representatives(std::string_view name);
    Status set_representatives(Representatives representatives);
    Status set_camera(const RenderCamera& camera);
    Status set_exposure(float exposure);

private:
    // Applies `edit` to a copy and keeps it if the renderer would accept it.
    template <typename Edit>
    Status edit(Edit edit);

    ViewState view_;
};

}  // namespace lc::client

#include "editor_client/editor/view_settings.h"

#include <string>

#include "editor_client/render/render_inputs.h"

namespace lc::client {

// Applied to a copy of the view and kept if the renderer would accept it
// (with the error ratio inside the editor control's range).
template <typename Edit>
Status ViewSettings::edit(Edit edit) {
    ViewState next = view_;
    edit(next);
    ValidationContext context;
    context.min_error_ratio = float(kMinErrorRatio);
    context.max_error_ratio = float(kMaxErrorRatio);
    Status valid = validate(render_settings_for(next, 1, 1, true), context);
    if (valid) view_ = next;
    return valid;
}

Status ViewSettings::set_mode(std::string_view name) {
    std::optional<RenderMode> mode = parse_render_mode(name);
    if (!mode)
        return make_error("unknown mode '" + std::string(name) + "' (" + names_in(kRenderModeNames) + ")");
    view_.mode = *mode;
    return Ok{};
}

Status ViewSettings::set_criterion(std::string_view name) {
    std::optional<CutCriterion> criterion = parse_criterion(name);
    if (!criterion)
        return make_error("unknown criterion '" + std::string(name) + "' (" + names_in(kCriterionNames) +
                          ")");
    // Validated: the radius criterion cannot take per-pixel representatives.
    return edit([&](ViewState& v) { v.criterion = *criterion; });
}

Status ViewSettings::set_error_ratio(double ratio) {
    return edit([&](ViewState& v) { v.error_ratio = ratio; });
}

Status ViewSettings::set_max_cut(uint32_t max_cut) {
    return edit([&](ViewState& v) { v.max_cut = max_cut; });
}

Status ViewSettings::set_realtime_cut(uint32_t nodes) {
    return edit([&](ViewState& v) { v.realtime_cut = nodes; });
}

Status ViewSettings::set_realtime_rays(uint32_t rays) {
    return edit([&](ViewState& v) { v.realtime_rays = rays; });
}

Status ViewSettings::set_restir(const RestirSettings& restir) {
    if (Status valid = validate(restir); !valid) return valid;
    return edit([&](ViewState& v) { v.restir = restir; });
}

Status ViewSettings::set_representatives(std::string_view name) {
    std::optional<Representatives> representatives = parse_representatives(name);
    if (!representatives)
        return make_error("unknown representatives '" + std::string(name) + "' (" +
                          names_in(kRepresentativesNames) + ")");
    return set_representatives(*representatives);
}

Status ViewSettings::set_representatives(Representatives representatives) {
    return edit([&](ViewState& v) { v.representatives = representatives; });
}

Status ViewSettings::set_camera(const RenderCamera& camera) {
    return edit([&](ViewState& v) { v.camera = camera; });
}

Status ViewSettings::set_exposure(float exposure) {
    return edit([&](ViewState& v) { v.exposure = exposure; });
}

}  // namespace lc::client

#include "editor_client/editor/editor_panels.h"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <glm/geometric.hpp>

#include "editor_client/editor/picking.h"
#include "editor_client/render/settings/render_settings.h"
#include "lightcuts/device/limits.h"

namespace lc::client {
namespace {

// Lights placed by clicking sit this far off the surface (scene units), so
// they light it instead of sitting inside it.
constexpr float kClickLightOffset = 0.1f;
// A click selects a light within this angle of the ray (radians, ~2 degrees).
constexpr double kLightPickAngle = 0.035;

void report(PanelState& state, const Status& status, const std::string& success) {
    state.message_is_error = !status;
    state.message = status ? success : status.error();
}

glm::vec3 to_vec3(const std::array<float, 3>& a) {
    return {a[0], a[1], a[2]};
}

const char* const kLightTypes[] = {"point", "spot", "directional"};
const char* const kLayouts[] = {"random", "grid"};

// A list of an enum's names in its table's order: the entry picked, or none.
template <typename Enum, size_t N>
std::optional<Enum> enum_combo(const char* label, const NameTable<Enum, N>& table, Enum current) {
    const std::array<const char*, N> names = names_of(table);
    int index = int(index_in(table, current));
    if (!ImGui::Combo(label, &index, names.data(), int(N))) return std::nullopt;
    return table[size_t(index)].value;
}

void draw_view_panel(EditorSession& session, PanelState& state) {
    const ViewState& view = session.view();
    if (std::optional<RenderMode> mode = enum_combo("mode", kRenderModeNames, view.mode)) {
        session.view_settings().set_mode(*mode);
        report(state, Ok{}, std::string("mode ") + render_mode_name(*mode));
    }
    if (mode_needs_tree(view.mode) && !session.tree_matches_scene())
        ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "no tree for these lights: showing reference");
    if (std::optional<CutCriterion> criterion = enum_combo("criterion", kCriterionNames, view.criterion))
        report(state, session.view_settings().set_criterion(criterion_name(*criterion)),
               std::string("criterion ") + criterion_name(*criterion));
    float ratio = float(view.error_ratio);
    if (ImGui::SliderFloat("error ratio", &ratio, float(kMinErrorRatio), 0.2f, "%.4f",
                           ImGuiSliderFlags_Logarithmic))
        report(state, session.view_settings().set_error_ratio(ratio), "error ratio set");
    int max_cut = int(view.max_cut);
    if (ImGui::SliderInt("max cut", &max_cut, 1, 4096, "%d", ImGuiSliderFlags_Logarithmic))
        report(state, session.view_settings().set_max_cut(uint32_t(std::max(max_cut, 1))), "max cut set");
    if (view.mode == RenderMode::kRealtime) {
        // Shadow rays per pixel and frame: the real-time mode's whole budget.
        int nodes = int(view.realtime_cut);
        if (ImGui::SliderInt("real-time cut", &nodes, 1, int(kMaxStochasticCut)))
            report(state, session.view_settings().set_realtime_cut(uint32_t(std::max(nodes, 1))), "real-time cut set");
        // 0 traces one ray per cut node; fewer rays are picked among the cut's lights.
        int rays = int(view.realtime_rays);
        if (ImGui::SliderInt("shadow rays", &rays, 0, int(kMaxStochasticRays)))
            report(state, session.view_settings().set_realtime_rays(uint32_t(std::max(rays, 0))), "shadow rays set");
    }
    if (view.criterion == CutCriterion::kBound) {
        // How a cluster is evaluated: importance keeps E = 0.005 within 2% at 99% of pixels
        // (docs/BENCHMARKS.md), at about twice the time of the tree's representatives.
        if (std::optional<Representatives> representatives =
                enum_combo("representatives", kRepresentativesNames, view.representatives))
            report(state, session.view_settings().set_representatives(*representatives),
                   std::string("representatives ") + representatives_name(*representatives));
    }
    float exposure = view.exposure;
    if (ImGui::SliderFloat("exposure", &exposure, 0.0f, 8.0f, "%.2f"))
        report(state, session.view_settings().set_exposure(exposure), "exposure set");
}

void draw_light_list(EditorSession& session, PanelState& state) {
    const std::vector<SceneLight>& lights = session.scene().lights;
    ImGui::Text("%zu lights", lights.size());
    std::optional<size_t> to_delete;
    if (ImGui::BeginListBox("##lights", ImVec2(-FLT_MIN, 6.0f * ImGui::GetTextLineHeight()))) {
        // Thousands of lights: only the visible rows are built.
        ImGuiListClipper clipper;
        clipper.Begin(int(lights.size()));
        while (clipper.Step()) {
            for (int i = clipper.DisplayStart; i < clipper.DisplayEnd; ++i) {
                const SceneLight& l = lights[size_t(i)];
                char label[160];
                std::snprintf(label, sizeof label, "%d %s (%.2f %.2f %.2f) %.3g%s", i,
                              kLightTypes[int(l.type)], l.position.x, l.position.y, l.position.z, l.intensity,
                              l.classic ? " classic" : "");
                const bool selected = session.edits().selection() == size_t(i);
                if (ImGui::Selectable(label, selected))
                    report(state, session.edits().select(size_t(i)), "selected light " + std::to_string(i));
            }
        }
        ImGui::EndListBox();
    }
    if (std::optional<size_t> selected = session.edits().selection()) {
        const SceneLight& light = lights[*selected];
        float position[3] = {light.position.x, light.position.y, light.position.z};
        if (ImGui::DragFloat3("move", position, 0.05f))
            report(state, session.edits().move_light(*selected, {position[0], position[1], position[2]}),
                   "moved light " + std::to_string(*selected));
        if (ImGui::Button("Delete selected")) to_delete = *selected;
    }
    if (to_delete)
        report(state, session.edits().remove_light(*to_delete), "removed light " + std::to_string(*to_delete));
}

void draw_add_light(EditorSession& session, EditorHost& host, PanelState& state) {
    ImGui::Combo("type", &state.light_type, kLightTypes, IM_ARRAYSIZE(kLightTypes));
    ImGui::InputFloat3("position", state.position.data());
    ImGui::SameLine();
    ImGui::Checkbox("click", &state.place_by_click);
    if (state.light_type != 0) ImGui::InputFloat3("direction", state.direction.data());
    ImGui::ColorEdit3("colour", state.color.data());
    ImGui::InputFloat("intensity", &state.intensity, 1.0f, 10.0f, "%.3g");
    ImGui::InputFloat("range (0: none)", &state.range, 0.5f, 2.0f, "%.3g");
    ImGui::Checkbox("classic (outside the tree)", &state.classic);
    if (ImGui::Button("Add light")) {
        SceneLight light;
        light.type = LightType(state.light_type);
        light.position = to_vec3(state.position);
        const glm::vec3 direction = to_vec3(state.direction);
        const float length = std::sqrt(glm::dot(direction, direction));
        // The session validates the rest; a zero direction is named there.
        light.direction = length > 0.0f ? direction / length : direction;
        light.color = to_vec3(state.color);
        light.intensity = state.intensity;
        light.range = state.range;
        light.classic = state.classic;
        Result<size_t> added = session.edits().add_light(light);
        if (added)
            report(state, Ok{}, "added light " + std::to_string(*added));
        else
            report(state, make_error(added.error()), "");
    }
    ImGui::Separator();
    ImGui::InputInt("count", &state.procedural_count);
    ImGui::Combo("layout", &state.procedural_layout, kLayouts, IM_ARRAYSIZE(kLayouts));
    ImGui::InputInt("seed", &state.procedural_seed);
    if (ImGui::Button("Add procedural lights")) {
        cmd::AddLights add;
        add.count = uint32_t(std::max(state.procedural_count, 0));
        add.layout = LightLayout(state.procedural_layout);
        add.seed = uint64_t(std::max(state.procedural_seed, 0));
        add.type = LightTypeChoice(std::clamp(state.light_type, 0, 2));
        if (state.intensity > 0.0f) add.intensity = state.intensity;
        add.range = state.range;
        // Through the script's command path, so both place lights alike.
        report(state, execute_editor_command(add, session, host),
               "added " + std::to_string(add.count) + " lights");
    }
}

void draw_bake_panel(EditorSession& session, PanelState& state) {
    ImGui::TextUnformatted(session.baking().server_description().c_str());
    if (session.baking().bake_running()) {
        const BakeProgress progress = session.baking().bake_progress().value_or(BakeProgress{});
        char text[96];
        std::snprintf(text, sizeof text, "%s %.0f%%",
                      progress.stage.empty() ? "connecting" : progress.stage.c_str(),
                      double(progress.percent));
        ImGui::ProgressBar(std::clamp(progress.percent / 100.0f, 0.0f, 1.0f), ImVec2(-FLT_MIN, 0), text);
        if (ImGui::Button("Cancel")) session.baking().cancel_bake();
    } else {
        const char* const methods[] = {"off", "VPL (instant radiosity)", "radiosity (patches)"};
        int method = int(session.baking().indirect());
        if (ImGui::Combo("indirect light", &method, methods, IM_ARRAYSIZE(methods)))
            session.baking().set_indirect(IndirectMethod(method));
        ImGui::BeginDisabled(!session.baking().has_server());
        if (ImGui::Button("Build lighting"))
            report(state, session.start_bake(),
                   "baking " + std::to_string(session.scene().lights.size()) + " lights");
        ImGui::EndDisabled();
    }
    if (const std::optional<BakeReport>& last = session.baking().last_bake(); last && !last->succeeded)
        ImGui::TextColored(ImVec4(1.0f, 0.4f, 0.4f, 1.0f), "last bake %s: %s",
                           last->cancelled ? "cancelled" : "failed", last->error.c_str());
}

// The server panel: the poller's latest lines; the poller follows the session's
// server (a spawned one appears at the first bake).
void draw_server_panel(EditorSession& session, PanelState& state) {
    std::optional<ServerStatusQuery> query = session.baking().status_query();
    if (!query) {
        state.server_status.reset();
        ImGui::TextUnformatted(session.baking().server_description().c_str());
        return;
    }
    if (!state.server_status || state.server_status->server() != query->server) {
        query->timeout_seconds = kServerStatusTimeoutSeconds;
        state.server_status = std::make_shared<ServerStatusPoller>(*query, kServerStatusInterval);
    }
    ImGui::PushTextWrapPos(0.0f);  // a bake's stage can be longer than the panel is wide
    for (const std::string& line : state.server_status->lines()) ImGui::TextUnformatted(line.c_str());
    ImGui::PopTextWrapPos();
}

void draw_file_panel(EditorSession& session, PanelState& state) {
    ImGui::BeginDisabled(session.edits().undo_stack().undo_depth() == 0);
    if (ImGui::Button("Undo")) report(state, session.edits().undo(), "undone");
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::InputText("##save", state.save_path.data(), state.save_path.size());
    ImGui::SameLine();
    if (ImGui::Button("Save")) {
        const std::string path(state.save_path.data());
        report(state, session.edits().save(path), "saved " + path);
    }
}

}  // namespace

bool apply_view_click(EditorSession& session, PanelState& state, const ViewClick& click) {
    const Ray ray =
        camera_ray(session.view().camera, click.x, click.y, click.window_width, click.window_height);
    if (state.place_by_click) {
        const std::optional<SurfaceHit> hit = pick_surface(session.scene(), ray);
        if (!hit) {
            report(state, make_error("the click hit no surface"), "");
            return false;
        }
        const glm::vec3 p = light_position_above(*hit, kClickLightOffset);
        state.position = {p.x, p.y, p.z};
        state.place_by_click = false;
        report(state, Ok{}, "position picked on the surface");
        return true;
    }
    const std::optional<size_t> light = pick_light(session.scene(), ray, kLightPickAngle);
    if (!light) return false;
    report(state, session.edits().select(*light), "selected light " + std::to_string(*light));
    return true;
}

void draw_editor_panels(EditorSession& session, EditorHost& host, PanelState& state, const FrameInfo& frame,
                        const std::optional<ViewClick>& click) {
    if (click) apply_view_click(session, state, *click);
    if (state.save_path[0] == '\0')
        std::snprintf(state.save_path.data(), state.save_path.size(), "%s", "edited.gltf");

    ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
    ImGui::SetNextWindowSize(ImVec2(340, 0), ImGuiCond_FirstUseEver);
    ImGui::Begin("Lightcuts editor");
    if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) draw_view_panel(session, state);
    if (ImGui::CollapsingHeader("Build lighting", ImGuiTreeNodeFlags_DefaultOpen))
        draw_bake_panel(session, state);
    if (ImGui::CollapsingHeader("Server", ImGuiTreeNodeFlags_DefaultOpen)) draw_server_panel(session, state);
    if (ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen)) draw_light_list(session, state);
    if (ImGui::CollapsingHeader("Add light")) draw_add_light(session, host, state);
    if (ImGui::CollapsingHeader("File", ImGuiTreeNodeFlags_DefaultOpen)) draw_file_panel(session, state);
    if (!state.message.empty()) {
        const ImVec4 colour =
            state.message_is_error ? ImVec4(1.0f, 0.4f, 0.4f, 1.0f) : ImVec4(0.6f, 1.0f, 0.6f, 1.0f);
        ImGui::PushTextWrapPos(0.0f);
        ImGui::TextColored(colour, "%s", state.message.c_str());
        ImGui::PopTextWrapPos();
    }
    ImGui::End();

    // The overlay: top right, no decoration, not movable.
    const ImGuiViewport* viewport = ImGui::GetMainViewport();
    ImGui::SetNextWindowPos(
        ImVec2(viewport->WorkPos.x + viewport->WorkSize.x - 8.0f, viewport->WorkPos.y + 8.0f),
        ImGuiCond_Always, ImVec2(1.0f, 0.0f));
    ImGui::SetNextWindowBgAlpha(0.55f);
    ImGui::Begin("overlay", nullptr,
                 ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                     ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                     ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove);
    for (const std::string& line : overlay_lines(session, frame)) ImGui::TextUnformatted(line.c_str());
    ImGui::End();
}

}  // namespace lc::client

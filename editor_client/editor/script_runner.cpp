#include "editor_client/editor/script_runner.h"

#include <type_traits>
#include <utility>

namespace lc::client {
namespace {

// Procedural lights fill the scene's bounds, 5% in from each side (the
// add-lights command's default), or a unit box around the origin.
LightLayoutOptions layout_in_scene(const cmd::AddLights& c, const Scene& scene) {
    LightLayoutOptions options;
    options.count = c.count;
    options.layout = c.layout;
    options.seed = c.seed;
    options.type = c.type;
    options.intensity = c.intensity;
    options.range = c.range;
    options.surfaces = &scene;
    if (c.layout == LightLayout::kSurface) {
        // The surface layout samples the scene's triangles: every surface counts.
        options.box_min = scene.bounds_min;
        options.box_max = scene.bounds_max;
    } else if (scene.bounds_min == scene.bounds_max) {
        options.box_min = scene.bounds_min - glm::vec3(1.0f);
        options.box_max = scene.bounds_max + glm::vec3(1.0f);
    } else {
        const glm::vec3 inset = (scene.bounds_max - scene.bounds_min) * 0.05f;
        options.box_min = scene.bounds_min + inset;
        options.box_max = scene.bounds_max - inset;
    }
    return options;
}

Status as_status(const Result<size_t>& result) {
    if (!result) return make_error(result.error());
    return Ok{};
}

}  // namespace

Status execute_editor_command(const EditorCommand& command, EditorSession& session,
                              EditorHost& host) {
    return std::visit(
        [&](const auto& c) -> Status {
            using T = std::decay_t<decltype(c)>;
            if constexpr (std::is_same_v<T, cmd::AddLight>) {
                return as_status(session.edits().add_light(c.light));
            } else if constexpr (std::is_same_v<T, cmd::AddLights>) {
                return as_status(
                    session.edits().add_procedural_lights(layout_in_scene(c, session.scene())));
            } else if constexpr (std::is_same_v<T, cmd::RemoveLight>) {
                return session.edits().remove_light(c.index);
            } else if constexpr (std::is_same_v<T, cmd::MoveLight>) {
                return session.edits().move_light(c.index, c.position);
            } else if constexpr (std::is_same_v<T, cmd::Select>) {
                return session.edits().select(c.index);
            } else if constexpr (std::is_same_v<T, cmd::Undo>) {
                return session.edits().undo();
            } else if constexpr (std::is_same_v<T, cmd::Redo>) {
                return session.edits().redo();
            } else if constexpr (std::is_same_v<T, cmd::Bake>) {
                return session.start_bake();
            } else if constexpr (std::is_same_v<T, cmd::CancelBake>) {
                session.baking().cancel_bake();
                return Ok{};
            } else if constexpr (std::is_same_v<T, cmd::Mode>) {
                return session.view_settings().set_mode(c.name);
            } else if constexpr (std::is_same_v<T, cmd::Criterion>) {
                return session.view_settings().set_criterion(c.name);
            } else if constexpr (std::is_same_v<T, cmd::ErrorRatio>) {
                return session.view_settings().set_error_ratio(c.ratio);
            } else if constexpr (std::is_same_v<T, cmd::MaxCut>) {
                return session.view_settings().set_max_cut(c.max_cut);
            } else if constexpr (std::is_same_v<T, cmd::RealtimeCut>) {
                return session.view_settings().set_realtime_cut(c.nodes);
            } else if constexpr (std::is_same_v<T, cmd::RealtimeRays>) {
                return session.view_settings().set_realtime_rays(c.rays);
            } else if constexpr (std::is_same_v<T, cmd::RepresentativesChoice>) {
                return session.view_settings().set_representatives(c.name);
            } else if constexpr (std::is_same_v<T, cmd::Exposure>) {
                return session.view_settings().set_exposure(c.exposure);
            } else if constexpr (std::is_same_v<T, cmd::Camera>) {
                RenderCamera camera = c.camera;
                camera.up = session.view().camera.up;
                return session.view_settings().set_camera(camera);
            } else if constexpr (std::is_same_v<T, cmd::Screenshot>) {
                return host.screenshot(c.path);
            } else if constexpr (std::is_same_v<T, cmd::Save>) {
                return session.edits().save(c.path);
            } else if constexpr (std::is_same_v<T, cmd::SaveView>) {
                return host.save_view(c.path);
            } else if constexpr (std::is_same_v<T, cmd::WaitFrames> || std::is_same_v<T, cmd::WaitRefined>) {
                return Ok{};  // the runner waits; a single command has nothing to wait for
            } else {
                static_assert(std::is_same_v<T, cmd::Quit>);
                host.request_quit();
                return Ok{};
            }
        },
        command);
}

ScriptRunner::ScriptRunner(std::vector<ScriptLine> lines, std::string name)
    : lines_(std::move(lines)), name_(std::move(name)) {}

ScriptState ScriptRunner::fail(const ScriptLine& line, const std::string& message) {
    error_ = name_ + ":" + std::to_string(line.line) + ": " + message;
    state_ = ScriptState::kFailed;
    return state_;
}

ScriptState ScriptRunner::step(EditorSession& session, EditorHost& host) {
    if (state_ == ScriptState::kFinished || state_ == ScriptState::kQuit ||
        state_ == ScriptState::kFailed)
        return state_;
    if (waiting_for_bake_) {
        // The frame loop polls the session; poll here too for loops that do not.
        std::optional<BakeReport> report = session.baking().poll_bake();
        if (session.baking().bake_running()) return state_ = ScriptState::kWaiting;
        waiting_for_bake_ = false;
        const ScriptLine& bake_line = lines_[next_ - 1];
        if (!report) report = session.baking().last_bake();
        if (!report) return fail(bake_line, "the bake ended without a report");
        if (!report->succeeded) return fail(bake_line, "bake failed: " + report->error);
    }
    // This step is a frame of its own: the frames waited for count down here.
    if (frames_to_wait_ > 0 && --frames_to_wait_ > 0) return state_ = ScriptState::kWaiting;
    if (waiting_for_refinement_) {
        if (!host.view_refined()) return state_ = ScriptState::kWaiting;
        waiting_for_refinement_ = false;
    }
    while (next_ < lines_.size()) {
        const ScriptLine& line = lines_[next_++];
        Status done = execute_editor_command(line.command, session, host);
        if (!done) return fail(line, done.error());
        if (std::holds_alternative<cmd::Quit>(line.command)) return state_ = ScriptState::kQuit;
        if (std::holds_alternative<cmd::Bake>(line.command)) {
            waiting_for_bake_ = true;
            return state_ = ScriptState::kWaiting;
        }
        if (const auto* wait = std::get_if<cmd::WaitFrames>(&line.command); wait && wait->frames > 0) {
            frames_to_wait_ = wait->frames;
            return state_ = ScriptState::kWaiting;
        }
        if (std::holds_alternative<cmd::WaitRefined>(line.command) && !host.view_refined()) {
            waiting_for_refinement_ = true;
            return state_ = ScriptState::kWaiting;
        }
    }
    return state_ = ScriptState::kFinished;
}

ScriptState run_script_to_end(ScriptRunner& runner, EditorSession& session, EditorHost& host) {
    while (true) {
        const ScriptState state = runner.step(session, host);
        if (state != ScriptState::kWaiting) return state;
        if (session.baking().bake_running()) session.baking().wait_for_bake();
    }
}

}  // namespace lc::client

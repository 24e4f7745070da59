#pragma once
// One editor command, as `--script FILE` spells it (one per line; PATH is the
// rest of the line, so it may hold spaces):
//   add-light TYPE X Y Z R G B INTENSITY [RANGE] [classic]
//   add-lights COUNT LAYOUT SEED [TYPE [INTENSITY [RANGE]]]   (procedural, in the scene bounds)
//   remove-light INDEX | move-light INDEX X Y Z | select INDEX | undo | redo
//   bake | cancel-bake
//   mode NAME | criterion NAME | error-ratio R | max-cut N | exposure E
//   camera EX EY EZ TX TY TZ FOVY          (FOVY in degrees)
//   screenshot PATH | save PATH | quit      (screenshot: PNG, or PFM of the radiance)
//   wait-frames N | wait-refined | save-view PATH   (the progressive view: let N frames
//   pass, wait until the image is complete, save it as refined so far)
// '#' starts a comment; blank lines are skipped.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "editor_client/render/settings/render_settings.h"
#include "editor_client/scene/scene_generator.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"

namespace lc::client {

namespace cmd {
struct AddLight {
    SceneLight light;  // GUID zero: the session assigns one
};
struct AddLights {
    uint32_t count = 0;
    LightLayout layout = LightLayout::kRandom;
    uint64_t seed = 0;
    LightTypeChoice type = LightTypeChoice::kPoint;
    std::optional<float> intensity;
    float range = 0.0f;
};
struct RemoveLight {
    size_t index = 0;
};
struct MoveLight {
    size_t index = 0;
    glm::vec3 position{0.0f};
};
struct Select {
    size_t index = 0;
};
struct Undo {};
struct Redo {};
struct Bake {};
struct CancelBake {};
struct Mode {
    std::string name;
};
struct Criterion {
    std::string name;
};
struct ErrorRatio {
    double ratio = 0.02;
};
struct MaxCut {
    uint32_t max_cut = 0;
};
struct RealtimeCut {
    uint32_t nodes = 16;
};
struct RealtimeRays {
    uint32_t rays = 0;
};
struct RepresentativesChoice {
    std::string name;
};
struct Exposure {
    float exposure = 1.0f;
};
struct Camera {
    RenderCamera camera;
};
struct Screenshot {
    std::filesystem::path path;
};
struct Save {
    std::filesystem::path path;
};
struct Quit {};
struct WaitFrames {
    uint32_t frames = 0;
};
struct WaitRefined {};
struct SaveView {
    std::filesystem::path path;
};
}  // namespace cmd

using EditorCommand =
    std::variant<cmd::AddLight, cmd::AddLights, cmd::RemoveLight, cmd::MoveLight, cmd::Select, cmd::Undo,
                 cmd::Redo, cmd::Bake, cmd::CancelBake, cmd::Mode, cmd::Criterion, cmd::ErrorRatio,
                 cmd::MaxCut, cmd::RealtimeCut, cmd::RealtimeRays, cmd::RepresentativesChoice, cmd::Exposure, cmd::Camera, cmd::Screenshot,
                 cmd::Save, cmd::Quit, cmd::WaitFrames, cmd::WaitRefined, cmd::SaveView>;

// One line without its comment; the error names the command and argument.
// An empty (or comment-only) line gives std::nullopt.
Result<std::optional<EditorCommand>> parse_editor_command(std::string_view line);

struct ScriptLine {
    size_t line = 0;   // 1-based line number in the script
    std::string text;  // the line as written, for messages
    EditorCommand command;
};

// Every error names the line number ("script.txt:3: ...").
Result<std::vector<ScriptLine>> parse_editor_script(std::string_view text,
                                                    const std::string& name = "script");
Result<std::vector<ScriptLine>> load_editor_script(const std::filesystem::path& path);

}  // namespace lc::client

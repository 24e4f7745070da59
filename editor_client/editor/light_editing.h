#pragma once
// The editor's scene and its light edits: add, remove, move, change, with
// undo and redo, the selection, and saving back to glTF. Every edit is
// all-or-nothing; an error names the light and the field.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "editor_client/editor/undo_stack.h"
#include "editor_client/scene/scene_generator.h"
#include "lightcuts/result.h"
#include "lightcuts/scene.h"

namespace lc::client {

class LightEditing {
public:
    explicit LightEditing(Scene scene);

    const Scene& scene() const { return scene_; }
    // Increments on every change of the scene's lights (edits, undo, redo).
    uint64_t scene_revision() const { return scene_revision_; }

    // A zero GUID gets a fresh one. Selects the new light; returns its index.
    Result<size_t> add_light(SceneLight light);
    // Procedural layout (options.guid_salt is set here); one undo step for
    // the whole batch. Returns the number of lights added.
    Result<size_t> add_procedural_lights(LightLayoutOptions options);
    Status remove_light(size_t index);
    Status move_light(size_t index, const glm::vec3& position);
    // Replaces every field but the GUID (type, colour, intensity, range, ...).
    Status update_light(size_t index, const SceneLight& light);
    Status undo();
    Status redo();
    const UndoStack& undo_stack() const { return undo_; }

    Status select(std::optional<size_t> index);
    std::optional<size_t> selection() const { return selection_; }

    // glTF with KHR_lights_punctual: a loaded file is copied with its lights
    // replaced; a generated scene is written whole.
    Status save(const std::filesystem::path& out) const;

private:
    EditSnapshot snapshot(std::string label) const;
    void restore(EditSnapshot snapshot);
    void lights_changed();
    Guid fresh_light_guid();
    Status check_index(size_t index, std::string_view action) const;

    Scene scene_;
    uint64_t scene_revision_ = 0;
    uint64_t guid_counter_ = 0;
    Guid guid_seed_;
    std::optional<size_t> selection_;
    UndoStack undo_;
};

// "point", "spot", "directional".
Result<LightType> parse_light_type(std::string_view text);

}  // namespace lc::client

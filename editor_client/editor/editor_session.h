#pragma once
// The editor without its window, as three parts behind a thin facade: the
// scene and its light edits (light_editing.h), what the view shows
// (view_settings.h), and the bakes with the imported tree (editor_baking.h).
// The ImGui panels and `--script` both call these, so a script exercises
// exactly the code paths a person does. Not thread-safe: owned and called by
// the UI thread; only the BakeJob works on a thread of its own.
#include <filesystem>
#include <memory>

#include "editor_client/bake/bake_client.h"
#include "editor_client/editor/editor_baking.h"
#include "editor_client/editor/light_editing.h"
#include "editor_client/editor/view_settings.h"
#include "lightcuts/result.h"
#include "lightcuts/scene.h"

namespace lc::client {

struct EditorSessionOptions {
    // Where bakes go: bake.server ("HOST:PORT"), or bake.spawn_server for a
    // local lightmass_server started at the first bake and kept until the
    // session ends. Neither: baking reports that no server is configured.
    BakeClientOptions bake;
    unsigned spawned_server_threads = 2;
    float aspect = 16.0f / 9.0f;  // for the default camera
};

class EditorSession {
public:
    explicit EditorSession(Scene scene, EditorSessionOptions options = {});

    LightEditing& edits() { return edits_; }
    const LightEditing& edits() const { return edits_; }
    ViewSettings& view_settings() { return view_; }
    const ViewSettings& view_settings() const { return view_; }
    EditorBaking& baking() { return baking_; }
    const EditorBaking& baking() const { return baking_; }

    // What most readers want of the parts.
    const Scene& scene() const { return edits_.scene(); }
    uint64_t scene_revision() const { return edits_.scene_revision(); }
    const ViewState& view() const { return view_.state(); }
    // The environment bakes send and the view shows as its background (null: none).
    const std::shared_ptr<const Environment>& environment() const { return baking_.environment(); }

    // Where the parts meet: the tree against the lights being edited.
    // False when lights changed since the tree was baked (or there is none).
    bool tree_matches_scene() const { return baking_.tree_matches(scene()); }
    // A result channel dump (bake -o), taken as matching the current scene.
    Status import_tree_dump(const std::filesystem::path& path) { return baking_.import_tree_dump(path, scene()); }
    // Starts a bake of the current lights in the background.
    Status start_bake() { return baking_.start_bake(scene()); }

private:
    LightEditing edits_;
    ViewSettings view_;
    EditorBaking baking_;
};

}  // namespace lc::client

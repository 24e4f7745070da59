#pragma once
// The editor without its window: the scene being edited, the imported light
// tree, what the view shows, the selection, undo, and the bake in flight.
// The ImGui panels and `--script` both call these functions, so a script
// exercises exactly the code paths a person does. Not thread-safe: owned and
// called by the UI thread; only the BakeJob works on a thread of its own.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "editor_client/bake/bake_client.h"
#include "editor_client/bake/server_process.h"
#include "editor_client/bake/tree_store.h"
#include "editor_client/editor/bake_job.h"
#include "editor_client/editor/undo_stack.h"
#include "editor_client/editor/view_state.h"
#include "lightcuts/scene.h"
#include "editor_client/scene/scene_generator.h"
#include "lightcuts/result.h"

namespace lc::client {

struct EditorSessionOptions {
    // Where bakes go: bake.server ("HOST:PORT"), or bake.spawn_server for a
    // local lightmass_server started at the first bake and kept until the
    // session ends. Neither: baking reports that no server is configured.
    BakeClientOptions bake;
    unsigned spawned_server_threads = 2;
    float aspect = 16.0f / 9.0f;  // for the default camera
};

// How the last finished bake went, for the overlay and the status line.
struct BakeReport {
    bool succeeded = false;
    bool cancelled = false;
    std::string error;  // when !succeeded
    std::vector<std::string> warnings;
    size_t light_count = 0;  // lights sent
    size_t node_count = 0;   // tree nodes received
    double total_ms = 0.0;   // upload, build and download
    double build_ms = 0.0;   // on the server
};

class EditorSession {
public:
    explicit EditorSession(Scene scene, EditorSessionOptions options = {});
    // The environment bakes send and the view shows as its background (null: none).
    const std::shared_ptr<const Environment>& environment() const { return options_.bake.environment; }
    ~EditorSession();
    EditorSession(const EditorSession&) = delete;
    EditorSession& operator=(const EditorSession&) = delete;

    const Scene& scene() const { return scene_; }
    // Increments on every change of the scene's lights (edits, undo, redo).
    uint64_t scene_revision() const { return scene_revision_; }

    // --- Light edits: all-or-nothing; the error names the light and field. ---
    // A zero GUID gets a fresh one. Selects the new light; returns its index.
    Result<size_t> add_light(SceneLight light);
    // Procedural layout (options.guid_salt is set by the session); one undo
    // step for the whole batch. Returns the number of lights added.
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

    // --- View ---
    const ViewState& view() const { return view_; }
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
    // tree, pixel or importance (render --representatives); per-pixel draws need the bound criterion.
    Status set_representatives(std::string_view name);
    Status set_camera(const RenderCamera& camera);
    Status set_exposure(float exposure);

    // --- Light tree ---
    std::shared_ptr<const LightTree> tree() const { return trees_.current(); }
    uint64_t tree_generation() const { return trees_.generation(); }
    // False when lights changed since the tree was baked (or there is none).
    bool tree_matches_scene() const;
    // A result channel dump (bake -o), taken as matching the current scene.
    Status import_tree_dump(const std::filesystem::path& path);

    // --- Bake ---
    bool has_server() const;
    // For the status line: "HOST:PORT", "local 127.0.0.1:PORT", or why there is none.
    std::string server_description() const;
    // The bounced light the next bake adds (the bake panel's choice; --indirect).
    IndirectMethod indirect() const { return options_.bake.indirect.method; }
    void set_indirect(IndirectMethod method) { options_.bake.indirect.method = method; }
    // Starts a bake of the current lights in the background.
    Status start_bake();
    void cancel_bake();
    bool bake_running() const { return job_ != nullptr; }
    std::optional<BakeProgress> bake_progress() const;
    // Call once per frame: when the running bake has finished, imports its
    // tree (or keeps the old one on failure) and returns the report.
    std::optional<BakeReport> poll_bake();
    // Blocks until the running bake finishes, then polls it.
    std::optional<BakeReport> wait_for_bake();
    const std::optional<BakeReport>& last_bake() const { return last_bake_; }

    // --- Files ---
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
    EditorSessionOptions options_;
    uint64_t scene_revision_ = 0;
    uint64_t guid_counter_ = 0;
    Guid guid_seed_;
    std::optional<size_t> selection_;
    UndoStack undo_;
    ViewState view_;

    TreeStore trees_;
    Guid tree_scene_guid_;
    bool has_tree_ = false;
    std::optional<BakeReport> last_bake_;

    // Declared before job_, so a running bake is cancelled and joined before
    // the server it talks to is stopped.
    std::unique_ptr<ServerProcess> spawned_server_;
    std::unique_ptr<BakeJob> job_;
};

// "point", "spot", "directional".
Result<LightType> parse_light_type(std::string_view text);

}  // namespace lc::client

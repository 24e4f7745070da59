#pragma once
// The editor's bakes: where they go (a server given, or a local one started
// at the first bake and kept until the session ends), the bake running in
// the background, and the imported light tree with the scene it was baked from.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "editor_client/bake/bake_client.h"
#include "editor_client/bake/server_process.h"
#include "editor_client/bake/server_status.h"
#include "editor_client/bake/tree_store.h"
#include "editor_client/editor/bake_job.h"
#include "lightcuts/result.h"
#include "lightcuts/scene.h"

namespace lc::client {

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

class EditorBaking {
public:
    // `spawned_server_threads`: the worker threads of a server started here.
    EditorBaking(BakeClientOptions options, unsigned spawned_server_threads);
    ~EditorBaking();
    EditorBaking(const EditorBaking&) = delete;
    EditorBaking& operator=(const EditorBaking&) = delete;

    // The environment bakes send (null: none).
    const std::shared_ptr<const Environment>& environment() const { return options_.environment; }

    std::shared_ptr<const LightTree> tree() const { return trees_.current(); }
    uint64_t tree_generation() const { return trees_.generation(); }
    // False when `scene` changed since the tree was baked (or there is none).
    bool tree_matches(const Scene& scene) const { return has_tree_ && tree_scene_guid_ == scene.guid; }
    // A result channel dump (bake -o), taken as baked from `scene`.
    Status import_tree_dump(const std::filesystem::path& path, const Scene& scene);

    bool has_server() const;
    // For the status line: "HOST:PORT", "local 127.0.0.1:PORT", or why there is none.
    std::string server_description() const;
    // How to ask the server bakes go to for its status (the panel's poller); none
    // before a spawned server has started.
    std::optional<ServerStatusQuery> status_query() const;
    // The bounced light the next bake adds (the bake panel's choice; --indirect).
    IndirectMethod indirect() const { return options_.indirect.method; }
    void set_indirect(IndirectMethod method) { options_.indirect.method = method; }

    // Starts a bake of `scene`'s lights in the background.
    Status start_bake(const Scene& scene);
    void cancel_bake();
    bool bake_running() const { return job_ != nullptr; }
    std::optional<BakeProgress> bake_progress() const;
    // Call once per frame: when the running bake has finished, imports its
    // tree (or keeps the old one on failure) and returns the report.
    std::optional<BakeReport> poll_bake();
    // Blocks until the running bake finishes, then polls it.
    std::optional<BakeReport> wait_for_bake();
    const std::optional<BakeReport>& last_bake() const { return last_bake_; }

private:
    BakeClientOptions options_;
    unsigned spawned_server_threads_ = 2;
    TreeStore trees_;
    Guid tree_scene_guid_;
    bool has_tree_ = false;
    std::optional<BakeReport> last_bake_;
    // Declared before job_, so a running bake is cancelled and joined before
    // the server it talks to is stopped.
    std::unique_ptr<ServerProcess> spawned_server_;
    std::unique_ptr<BakeJob> job_;
};

}  // namespace lc::client

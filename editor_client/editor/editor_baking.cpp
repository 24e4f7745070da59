#include "editor_client/editor/editor_baking.h"

#include <utility>

#include "editor_client/scene/surface_geometry.h"

namespace lc::client {

EditorBaking::EditorBaking(BakeClientOptions options, unsigned spawned_server_threads)
    : options_(std::move(options)), spawned_server_threads_(spawned_server_threads) {}

EditorBaking::~EditorBaking() = default;

Status EditorBaking::import_tree_dump(const std::filesystem::path& path, const Scene& scene) {
    Status imported = trees_.import_dump(path);
    if (!imported) return imported;
    has_tree_ = true;
    tree_scene_guid_ = scene.guid;
    return Ok{};
}

// --- Bake ---

bool EditorBaking::has_server() const {
    return options_.spawn_server || !options_.server.empty();
}

std::string EditorBaking::server_description() const {
    if (options_.spawn_server)
        return spawned_server_ ? "local " + spawned_server_->address()
                               : "local (started at the first bake)";
    if (!options_.server.empty()) return options_.server;
    return "none (--server HOST:PORT or --spawn-server)";
}

std::optional<ServerStatusQuery> EditorBaking::status_query() const {
    ServerStatusQuery query;
    if (options_.spawn_server) {
        if (!spawned_server_) return std::nullopt;
        query.server = spawned_server_->address();
    } else {
        if (options_.server.empty()) return std::nullopt;
        query.server = options_.server;
        query.tls = options_.tls;
        query.tls_ca_file = options_.tls_ca_file;
    }
    query.token_file = options_.token_file;
    return query;
}

Status EditorBaking::start_bake(const Scene& scene) {
    if (job_) return make_error("a bake is already running; cancel it or wait for it");
    if (!has_server())
        return make_error(
            "no bake server: start the editor with --server HOST:PORT or "
            "--spawn-server");
    BakeClientOptions bake = options_;
    bake.geometry = geometry_the_bake_needs(scene, bake.indirect.method);
    if (bake.spawn_server) {
        // One local server for the whole session, started at the first bake.
        if (!spawned_server_) {
            Result<std::unique_ptr<ServerProcess>> server =
                ServerProcess::spawn(spawned_server_threads_,
                                     spawned_server_flags(bake.ranks, bake.spawned_server_args));
            if (!server) return make_error("cannot start a local server: " + server.error());
            spawned_server_ = std::move(server.value());
        }
        bake.spawn_server = false;
        bake.server = spawned_server_->address();
    }
    job_ = std::make_unique<BakeJob>(scene.lights, scene.guid, std::move(bake));
    return Ok{};
}

void EditorBaking::cancel_bake() {
    if (job_) job_->cancel();
}

std::optional<BakeProgress> EditorBaking::bake_progress() const {
    if (!job_) return std::nullopt;
    return job_->progress();
}

std::optional<BakeReport> EditorBaking::poll_bake() {
    if (!job_ || !job_->finished()) return std::nullopt;
    job_->wait();  // the thread has stored its outcome; join it
    BakeReport report;
    report.light_count = job_->light_count();
    report.warnings = job_->warnings();
    const Guid baked_scene = job_->scene_guid();
    Result<BakeOutcome> outcome = job_->take_outcome();
    job_.reset();

    if (outcome) {
        report.node_count = outcome->tree.nodes.size();
        report.total_ms = outcome->total_ms;
        report.build_ms = outcome->done.build_ms;
    }
    // Import swaps the whole tree or nothing: a failed bake keeps the old one.
    Status imported = trees_.import(std::move(outcome));
    if (imported) {
        report.succeeded = true;
        has_tree_ = true;
        tree_scene_guid_ = baked_scene;
    } else {
        report.error = imported.error();
        report.cancelled = imported.error_kind() == ErrorKind::kCancelled;
    }
    last_bake_ = report;
    return report;
}

std::optional<BakeReport> EditorBaking::wait_for_bake() {
    if (!job_) return std::nullopt;
    job_->wait();
    return poll_bake();
}

}  // namespace lc::client

#include "editor_client/editor/editor_session.h"

#include <cmath>
#include <glm/geometric.hpp>
#include <set>
#include <utility>

#include "editor_client/render/render_inputs.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/gltf/gltf_writer.h"
#include "editor_client/scene/light_edit.h"
#include "editor_client/scene/surface_geometry.h"
#include "editor_client/scene/inputs/scene_guid.h"
#include "protocol/channel_records.h"

namespace lc::client {
namespace {

bool finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::string vec_text(const glm::vec3& v) {
    return "(" + std::to_string(v.x) + ", " + std::to_string(v.y) + ", " + std::to_string(v.z) +
           ")";
}

// Applies `edit` to a copy of the view and keeps it if the renderer would
// accept it (with the error ratio inside the editor control's range).
template <typename Edit>
Status edit_view(ViewState& view, Edit edit) {
    ViewState next = view;
    edit(next);
    ValidationContext context;
    context.min_error_ratio = float(kMinErrorRatio);
    context.max_error_ratio = float(kMaxErrorRatio);
    Status valid = validate(render_settings_for(next, 1, 1, true), context);
    if (valid) view = next;
    return valid;
}

}  // namespace

Result<LightType> parse_light_type(std::string_view text) {
    if (text == "point") return LightType::kPoint;
    if (text == "spot") return LightType::kSpot;
    if (text == "directional") return LightType::kDirectional;
    return make_error("unknown light type '" + std::string(text) + "' (point, spot, directional)");
}

EditorSession::EditorSession(Scene scene, EditorSessionOptions options)
    : scene_(std::move(scene)), options_(std::move(options)), guid_seed_(scene_.guid) {
    Result<RenderCamera> camera = choose_camera(scene_, "", std::nullopt, options_.aspect);
    view_.camera = camera ? camera.value() : frame_scene_bounds(scene_, options_.aspect);
}

EditorSession::~EditorSession() = default;

// --- Light edits ---

EditSnapshot EditorSession::snapshot(std::string label) const {
    return EditSnapshot{std::move(label), scene_.lights, selection_};
}

void EditorSession::restore(EditSnapshot snapshot) {
    scene_.lights = std::move(snapshot.lights);
    selection_ = snapshot.selection;
    if (selection_ && *selection_ >= scene_.lights.size()) selection_.reset();
    lights_changed();
}

void EditorSession::lights_changed() {
    update_scene_bounds(scene_);
    scene_.guid = compute_scene_guid(scene_);
    ++scene_revision_;
}

Guid EditorSession::fresh_light_guid() {
    std::set<Guid> used;
    for (const SceneLight& light : scene_.lights) used.insert(light.guid);
    // Deterministic: the session's starting scene and a counter.
    while (true) {
        const uint64_t n = guid_counter_++;
        const uint8_t bytes[] = {'e',
                                 'd',
                                 'i',
                                 't',
                                 uint8_t(guid_seed_.a),
                                 uint8_t(guid_seed_.a >> 8),
                                 uint8_t(guid_seed_.b),
                                 uint8_t(guid_seed_.b >> 8),
                                 uint8_t(guid_seed_.c),
                                 uint8_t(guid_seed_.c >> 8),
                                 uint8_t(guid_seed_.d),
                                 uint8_t(guid_seed_.d >> 8),
                                 uint8_t(guid_seed_.d >> 16),
                                 uint8_t(guid_seed_.d >> 24),
                                 uint8_t(n),
                                 uint8_t(n >> 8),
                                 uint8_t(n >> 16),
                                 uint8_t(n >> 24),
                                 uint8_t(n >> 32),
                                 uint8_t(n >> 40),
                                 uint8_t(n >> 48),
                                 uint8_t(n >> 56)};
        const Guid guid = Guid::from_bytes(bytes);
        if (!guid.is_zero() && !used.contains(guid)) return guid;
    }
}

Status EditorSession::check_index(size_t index, std::string_view action) const {
    if (index < scene_.lights.size()) return Ok{};
    return make_error("cannot " + std::string(action) + " light " + std::to_string(index) +
                      ": the scene has " + std::to_string(scene_.lights.size()) + " lights" +
                      (scene_.lights.empty()
                           ? std::string()
                           : " (indices 0 to " + std::to_string(scene_.lights.size() - 1) + ")"));
}

Result<size_t> EditorSession::add_light(SceneLight light) {
    if (light.guid.is_zero()) light.guid = fresh_light_guid();
    EditSnapshot before = snapshot("add light " + std::to_string(scene_.lights.size()));
    Status added = add_lights(scene_, std::span<const SceneLight>(&light, 1));
    if (!added) return make_error(added.error());
    undo_.push(std::move(before));
    selection_ = scene_.lights.size() - 1;
    ++scene_revision_;  // add_lights already refreshed bounds and GUID
    return scene_.lights.size() - 1;
}

Result<size_t> EditorSession::add_procedural_lights(LightLayoutOptions options) {
    // Salted with the scene's current content and a counter, so two batches
    // with one seed still get distinct GUIDs.
    options.guid_salt = Guid::combine(scene_.guid, fresh_light_guid());
    Result<std::vector<SceneLight>> lights = generate_lights(options);
    if (!lights) return make_error("cannot add lights: " + lights.error());
    EditSnapshot before = snapshot("add " + std::to_string(lights->size()) + " lights");
    Status added = add_lights(scene_, lights.value());
    if (!added) return make_error(added.error());
    undo_.push(std::move(before));
    ++scene_revision_;
    return lights->size();
}

Status EditorSession::remove_light(size_t index) {
    if (Status ok = check_index(index, "remove"); !ok) return ok;
    EditSnapshot before = snapshot("remove light " + std::to_string(index));
    const size_t indices[] = {index};
    Status removed = remove_lights_by_index(scene_, indices);
    if (!removed) return removed;
    undo_.push(std::move(before));
    // The selection follows its light; removing the selected one clears it.
    if (selection_) {
        if (*selection_ == index)
            selection_.reset();
        else if (*selection_ > index)
            --*selection_;
    }
    ++scene_revision_;
    return Ok{};
}

Status EditorSession::move_light(size_t index, const glm::vec3& position) {
    if (Status ok = check_index(index, "move"); !ok) return ok;
    if (!finite(position))
        return make_error("cannot move light " + std::to_string(index) + " to " +
                          vec_text(position) + ": the position is not finite");
    SceneLight light = scene_.lights[index];
    light.position = position;
    return update_light(index, light);
}

Status EditorSession::update_light(size_t index, const SceneLight& light) {
    if (Status ok = check_index(index, "change"); !ok) return ok;
    SceneLight updated = light;
    updated.guid = scene_.lights[index].guid;
    if (Status valid = validate_scene_light(updated, index); !valid)
        return make_error("cannot change light: " + valid.error());
    EditSnapshot before = snapshot("change light " + std::to_string(index));
    scene_.lights[index] = updated;
    undo_.push(std::move(before));
    lights_changed();
    return Ok{};
}

Status EditorSession::undo() {
    std::optional<EditSnapshot> target = undo_.undo(snapshot(""));
    if (!target) return make_error("nothing to undo");
    restore(std::move(*target));
    return Ok{};
}

Status EditorSession::redo() {
    std::optional<EditSnapshot> target = undo_.redo(snapshot(""));
    if (!target) return make_error("nothing to redo");
    restore(std::move(*target));
    return Ok{};
}

Status EditorSession::select(std::optional<size_t> index) {
    if (index) {
        if (Status ok = check_index(*index, "select"); !ok) return ok;
    }
    selection_ = index;
    return Ok{};
}

// --- View ---

Status EditorSession::set_mode(std::string_view name) {
    std::optional<RenderMode> mode = parse_render_mode(name);
    if (!mode) {
        std::string known;
        for (int m = 0; m < kRenderModeCount; ++m)
            known += std::string(m ? ", " : "") + render_mode_name(RenderMode(m));
        return make_error("unknown mode '" + std::string(name) + "' (" + known + ")");
    }
    view_.mode = *mode;
    return Ok{};
}

Status EditorSession::set_criterion(std::string_view name) {
    std::optional<CutCriterion> criterion = parse_criterion(name);
    if (!criterion)
        return make_error("unknown criterion '" + std::string(name) + "' (radius, bound)");
    // Validated: the radius criterion cannot take per-pixel representatives.
    return edit_view(view_, [&](ViewState& v) { v.criterion = *criterion; });
}

Status EditorSession::set_error_ratio(double ratio) {
    return edit_view(view_, [&](ViewState& v) { v.error_ratio = ratio; });
}

Status EditorSession::set_max_cut(uint32_t max_cut) {
    return edit_view(view_, [&](ViewState& v) { v.max_cut = max_cut; });
}

Status EditorSession::set_realtime_cut(uint32_t nodes) {
    return edit_view(view_, [&](ViewState& v) { v.realtime_cut = nodes; });
}

Status EditorSession::set_realtime_rays(uint32_t rays) {
    return edit_view(view_, [&](ViewState& v) { v.realtime_rays = rays; });
}

Status EditorSession::set_representatives(std::string_view name) {
    std::optional<Representatives> representatives = parse_representatives(name);
    if (!representatives)
        return make_error("unknown representatives '" + std::string(name) + "' (tree, pixel, importance)");
    return edit_view(view_, [&](ViewState& v) { v.representatives = *representatives; });
}

Status EditorSession::set_camera(const RenderCamera& camera) {
    return edit_view(view_, [&](ViewState& v) { v.camera = camera; });
}

Status EditorSession::set_exposure(float exposure) {
    return edit_view(view_, [&](ViewState& v) { v.exposure = exposure; });
}

// --- Light tree ---

bool EditorSession::tree_matches_scene() const {
    return has_tree_ && tree_scene_guid_ == scene_.guid;
}

Status EditorSession::import_tree_dump(const std::filesystem::path& path) {
    Status imported = trees_.import_dump(path);
    if (!imported) return imported;
    has_tree_ = true;
    tree_scene_guid_ = scene_.guid;
    return Ok{};
}

// --- Bake ---

bool EditorSession::has_server() const {
    return options_.bake.spawn_server || !options_.bake.server.empty();
}

std::string EditorSession::server_description() const {
    if (options_.bake.spawn_server)
        return spawned_server_ ? "local " + spawned_server_->address()
                               : "local (started at the first bake)";
    if (!options_.bake.server.empty()) return options_.bake.server;
    return "none (--server HOST:PORT or --spawn-server)";
}

Status EditorSession::start_bake() {
    if (job_) return make_error("a bake is already running; cancel it or wait for it");
    if (!has_server())
        return make_error(
            "no bake server: start the editor with --server HOST:PORT or "
            "--spawn-server");
    BakeClientOptions bake = options_.bake;
    bake.geometry = geometry_the_bake_needs(scene_, bake.indirect.method);
    if (bake.spawn_server) {
        // One local server for the whole session, started at the first bake.
        if (!spawned_server_) {
            Result<std::unique_ptr<ServerProcess>> server =
                ServerProcess::spawn(options_.spawned_server_threads,
                                     spawned_server_flags(bake.ranks, bake.spawned_server_args));
            if (!server) return make_error("cannot start a local server: " + server.error());
            spawned_server_ = std::move(server.value());
        }
        bake.spawn_server = false;
        bake.server = spawned_server_->address();
    }
    job_ = std::make_unique<BakeJob>(scene_.lights, scene_.guid, std::move(bake));
    return Ok{};
}

void EditorSession::cancel_bake() {
    if (job_) job_->cancel();
}

std::optional<BakeProgress> EditorSession::bake_progress() const {
    if (!job_) return std::nullopt;
    return job_->progress();
}

std::optional<BakeReport> EditorSession::poll_bake() {
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

std::optional<BakeReport> EditorSession::wait_for_bake() {
    if (!job_) return std::nullopt;
    job_->wait();
    return poll_bake();
}

// --- Files ---

Status EditorSession::save(const std::filesystem::path& out) const {
    if (out.empty()) return make_error("save needs a file name");
    std::error_code ec;
    if (!scene_.source.empty() && std::filesystem::is_regular_file(scene_.source, ec))
        return write_lights_into_gltf(scene_.source, scene_.lights, out);
    return write_scene_gltf(scene_, out);
}

}  // namespace lc::client

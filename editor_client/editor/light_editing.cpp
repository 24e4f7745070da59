#include "editor_client/editor/light_editing.h"

#include <cmath>
#include <set>
#include <utility>

#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/scene/inputs/scene_guid.h"
#include "editor_client/scene/light_edit.h"
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

}  // namespace

Result<LightType> parse_light_type(std::string_view text) {
    if (text == "point") return LightType::kPoint;
    if (text == "spot") return LightType::kSpot;
    if (text == "directional") return LightType::kDirectional;
    return make_error("unknown light type '" + std::string(text) + "' (point, spot, directional)");
}

LightEditing::LightEditing(Scene scene) : scene_(std::move(scene)), guid_seed_(scene_.guid) {}

EditSnapshot LightEditing::snapshot(std::string label) const {
    return EditSnapshot{std::move(label), scene_.lights, selection_};
}

void LightEditing::restore(EditSnapshot snapshot) {
    scene_.lights = std::move(snapshot.lights);
    selection_ = snapshot.selection;
    if (selection_ && *selection_ >= scene_.lights.size()) selection_.reset();
    lights_changed();
}

void LightEditing::lights_changed() {
    update_scene_bounds(scene_);
    scene_.guid = compute_scene_guid(scene_);
    ++scene_revision_;
}

Guid LightEditing::fresh_light_guid() {
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

Status LightEditing::check_index(size_t index, std::string_view action) const {
    if (index < scene_.lights.size()) return Ok{};
    return make_error("cannot " + std::string(action) + " light " + std::to_string(index) +
                      ": the scene has " + std::to_string(scene_.lights.size()) + " lights" +
                      (scene_.lights.empty()
                           ? std::string()
                           : " (indices 0 to " + std::to_string(scene_.lights.size() - 1) + ")"));
}

Result<size_t> LightEditing::add_light(SceneLight light) {
    if (light.guid.is_zero()) light.guid = fresh_light_guid();
    EditSnapshot before = snapshot("add light " + std::to_string(scene_.lights.size()));
    Status added = add_lights(scene_, std::span<const SceneLight>(&light, 1));
    if (!added) return make_error(added.error());
    undo_.push(std::move(before));
    selection_ = scene_.lights.size() - 1;
    ++scene_revision_;  // add_lights already refreshed bounds and GUID
    return scene_.lights.size() - 1;
}

Result<size_t> LightEditing::add_procedural_lights(LightLayoutOptions options) {
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

Status LightEditing::remove_light(size_t index) {
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

Status LightEditing::move_light(size_t index, const glm::vec3& position) {
    if (Status ok = check_index(index, "move"); !ok) return ok;
    if (!finite(position))
        return make_error("cannot move light " + std::to_string(index) + " to " +
                          vec_text(position) + ": the position is not finite");
    SceneLight light = scene_.lights[index];
    light.position = position;
    return update_light(index, light);
}

Status LightEditing::update_light(size_t index, const SceneLight& light) {
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

Status LightEditing::undo() {
    std::optional<EditSnapshot> target = undo_.undo(snapshot(""));
    if (!target) return make_error("nothing to undo");
    restore(std::move(*target));
    return Ok{};
}

Status LightEditing::redo() {
    std::optional<EditSnapshot> target = undo_.redo(snapshot(""));
    if (!target) return make_error("nothing to redo");
    restore(std::move(*target));
    return Ok{};
}

Status LightEditing::select(std::optional<size_t> index) {
    if (index) {
        if (Status ok = check_index(*index, "select"); !ok) return ok;
    }
    selection_ = index;
    return Ok{};
}

Status LightEditing::save(const std::filesystem::path& out) const {
    if (out.empty()) return make_error("save needs a file name");
    std::error_code ec;
    if (!scene_.source.empty() && std::filesystem::is_regular_file(scene_.source, ec))
        return write_lights_into_gltf(scene_.source, scene_.lights, out);
    return write_scene_gltf(scene_, out);
}

}  // namespace lc::client

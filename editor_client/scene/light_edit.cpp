#include "editor_client/scene/light_edit.h"

#include <charconv>
#include <map>
#include <set>
#include <string>

#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/inputs/scene_guid.h"
#include "protocol/channel_records.h"

namespace lc::client {
namespace {

void refresh(Scene& scene) {
    update_scene_bounds(scene);
    scene.guid = compute_scene_guid(scene);
}

std::vector<std::string_view> split_commas(std::string_view text) {
    std::vector<std::string_view> items;
    size_t start = 0;
    while (true) {
        const size_t comma = text.find(',', start);
        std::string_view item = text.substr(
            start, comma == std::string_view::npos ? std::string_view::npos : comma - start);
        while (!item.empty() && item.front() == ' ') item.remove_prefix(1);
        while (!item.empty() && item.back() == ' ') item.remove_suffix(1);
        items.push_back(item);
        if (comma == std::string_view::npos) break;
        start = comma + 1;
    }
    return items;
}

// Keeps the lights whose flag is false, in order.
void erase_flagged(Scene& scene, const std::vector<bool>& remove) {
    std::vector<SceneLight> kept;
    kept.reserve(scene.lights.size());
    for (size_t i = 0; i < scene.lights.size(); ++i) {
        if (!remove[i]) kept.push_back(scene.lights[i]);
    }
    scene.lights = std::move(kept);
}

}  // namespace

Status add_lights(Scene& scene, std::span<const SceneLight> lights) {
    std::set<Guid> guids;
    for (const SceneLight& light : scene.lights) guids.insert(light.guid);
    for (size_t i = 0; i < lights.size(); ++i) {
        const size_t index = scene.lights.size() + i;  // its index once added
        Status valid = validate_scene_light(lights[i], index);
        if (!valid) return Error{"cannot add light: " + valid.error()};
        if (lights[i].guid.is_zero()) {
            return make_error("cannot add light " + std::to_string(index) + ": its GUID is zero");
        }
        if (!guids.insert(lights[i].guid).second) {
            return make_error("cannot add light " + std::to_string(index) + ": GUID " +
                              lights[i].guid.to_hex() + " is already in the scene");
        }
    }
    scene.lights.insert(scene.lights.end(), lights.begin(), lights.end());
    refresh(scene);
    return Ok{};
}

Status remove_lights_by_index(Scene& scene, std::span<const size_t> indices) {
    std::vector<bool> remove(scene.lights.size(), false);
    for (size_t index : indices) {
        if (index >= scene.lights.size()) {
            return make_error("cannot remove light " + std::to_string(index) + ": the scene has " +
                              std::to_string(scene.lights.size()) + " lights (indices 0 to " +
                              (scene.lights.empty() ? std::string("none")
                                                    : std::to_string(scene.lights.size() - 1)) +
                              ")");
        }
        if (remove[index]) {
            return make_error("light index " + std::to_string(index) + " is given twice");
        }
        remove[index] = true;
    }
    erase_flagged(scene, remove);
    refresh(scene);
    return Ok{};
}

Status remove_lights_by_guid(Scene& scene, std::span<const Guid> guids) {
    std::map<Guid, size_t> where;
    for (size_t i = 0; i < scene.lights.size(); ++i) where.emplace(scene.lights[i].guid, i);
    std::vector<bool> remove(scene.lights.size(), false);
    for (const Guid& guid : guids) {
        auto found = where.find(guid);
        if (found == where.end()) {
            return make_error("cannot remove light " + guid.to_hex() +
                              ": no light of the scene has this GUID");
        }
        if (remove[found->second]) {
            return make_error("light GUID " + guid.to_hex() + " is given twice");
        }
        remove[found->second] = true;
    }
    erase_flagged(scene, remove);
    refresh(scene);
    return Ok{};
}

void remove_all_lights(Scene& scene) {
    scene.lights.clear();
    refresh(scene);
}

Result<std::vector<size_t>> parse_index_list(std::string_view text) {
    std::vector<size_t> indices;
    for (std::string_view item : split_commas(text)) {
        size_t value = 0;
        const char* end = item.data() + item.size();
        auto [ptr, ec] = std::from_chars(item.data(), end, value);
        if (item.empty() || ec != std::errc() || ptr != end) {
            return make_error("'" + std::string(item) +
                              "' is not a light index (expected a non-negative integer)");
        }
        indices.push_back(value);
    }
    return indices;
}

Result<std::vector<Guid>> parse_guid_list(std::string_view text) {
    std::vector<Guid> guids;
    for (std::string_view item : split_commas(text)) {
        std::optional<Guid> guid = Guid::parse(item);
        if (!guid) {
            return make_error("'" + std::string(item) + "' is not a GUID (expected 32 hex digits)");
        }
        guids.push_back(*guid);
    }
    return guids;
}

}  // namespace lc::client

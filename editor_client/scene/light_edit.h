#pragma once
// Adding and removing a scene's lights. Every edit is all-or-nothing: on error
// the scene is unchanged and the message names the offending light, index or
// GUID. A successful edit refreshes the scene's bounds and GUID.
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "lightcuts/scene.h"
#include "lightcuts/result.h"

namespace lc::client {

// Each light must pass lc::validate_scene_light and carry a non-zero GUID
// unique in the scene and among the new lights.
Status add_lights(Scene& scene, std::span<const SceneLight> lights);

// Indices into scene.lights; any order; out of range or repeated is an error.
Status remove_lights_by_index(Scene& scene, std::span<const size_t> indices);
// Every GUID must name a light of the scene, once.
Status remove_lights_by_guid(Scene& scene, std::span<const Guid> guids);
void remove_all_lights(Scene& scene);

// "3" or "3,5,7" -> indices; the error names the bad item.
Result<std::vector<size_t>> parse_index_list(std::string_view text);
// One GUID or a comma-separated list, 32 hex digits each, '-' allowed.
Result<std::vector<Guid>> parse_guid_list(std::string_view text);

}  // namespace lc::client

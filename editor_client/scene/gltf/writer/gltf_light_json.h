#pragma once
// Scene lights as KHR_lights_punctual JSON, for both writers. Each light
// gets its own node (position as translation, direction as the rotation
// taking -Z onto it) carrying extras.lightcuts_guid, so the loader gives it
// back the same GUID; the light carries extras.lightcuts_classic when classic.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <span>

#include "lightcuts/result.h"
#include "lightcuts/scene.h"

namespace lc::client {

inline constexpr const char* kLightsPunctualExtension = "KHR_lights_punctual";

// Why the lights cannot be written, if they cannot: invalid lights, oriented
// lights (glTF has no cosine emitter) and zero directions.
Status validate_lights_for_gltf(std::span<const SceneLight> lights);

// Light `index` of the extension's "lights" array.
nlohmann::json light_json(const SceneLight& light, size_t index);
// The node that places light `light_index`.
nlohmann::json light_node_json(const SceneLight& light, size_t light_index);

}  // namespace lc::client

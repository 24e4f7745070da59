#include "editor_client/scene/gltf/writer/gltf_light_json.h"

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cmath>
#include <string>

#include "editor_client/scene/gltf/gltf_json_values.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "protocol/channel_records.h"

namespace lc::client {
namespace {

using json = nlohmann::json;

// The unit quaternion turning -Z (a glTF node's light direction) onto `d`.
glm::dquat rotation_from_minus_z(const glm::dvec3& d) {
    const glm::dvec3 from(0.0, 0.0, -1.0);
    const double c = glm::dot(from, d);
    if (c < -1.0 + 1e-12) return glm::dquat(0.0, 1.0, 0.0, 0.0);  // half turn about X
    const glm::dvec3 axis = glm::cross(from, d);
    return glm::normalize(glm::dquat(1.0 + c, axis.x, axis.y, axis.z));
}

bool is_identity(const glm::dquat& q) {
    return std::abs(q.w - 1.0) < 1e-15 && q.x == 0.0 && q.y == 0.0 && q.z == 0.0;
}

}  // namespace

Status validate_lights_for_gltf(std::span<const SceneLight> lights) {
    for (size_t i = 0; i < lights.size(); ++i) {
        Status valid = validate_scene_light(lights[i], i);
        if (!valid) return Error{"cannot write light: " + valid.error()};
        // KHR_lights_punctual has no cosine emitter; oriented lights are
        // area-light samples the server makes, never scene lights.
        if (lights[i].type == LightType::kOriented) {
            return make_error("cannot write light " + std::to_string(i) +
                              ": glTF (KHR_lights_punctual) has no oriented light type");
        }
        if (glm::length(lights[i].direction) <= 0.0f) {
            return make_error("cannot write light " + std::to_string(i) + ": zero direction");
        }
    }
    return Ok{};
}

json light_json(const SceneLight& light, size_t index) {
    json j;
    j["name"] = "light_" + std::to_string(index);
    j["type"] = light_type_name(light.type);
    j["color"] = gltf_vec3_json(light.color);
    j["intensity"] = light.intensity;
    if (light.range > 0.0f) j["range"] = light.range;
    if (light.type == LightType::kSpot) {
        j["spot"] = {{"innerConeAngle", light.inner_cone_angle}, {"outerConeAngle", light.outer_cone_angle}};
    }
    if (light.classic) j["extras"] = {{kClassicExtrasKey, true}};
    return j;
}

json light_node_json(const SceneLight& light, size_t light_index) {
    json node;
    node["name"] = "light_" + std::to_string(light_index);
    node["translation"] = gltf_vec3_json(light.position);
    const glm::dquat q = rotation_from_minus_z(glm::normalize(glm::dvec3(light.direction)));
    if (!is_identity(q)) node["rotation"] = gltf_quat_json(q);
    node["extensions"] = {{kLightsPunctualExtension, {{"light", light_index}}}};
    node["extras"] = {{kGuidExtrasKey, light.guid.to_hex()}};
    return node;
}

}  // namespace lc::client

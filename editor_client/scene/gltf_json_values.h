#pragma once
// Small pieces of glTF JSON both writers make: vectors and quaternions as
// glTF spells them, and the extensionsUsed/extensionsRequired name lists.
#include <glm/gtc/quaternion.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>

namespace lc::client {

inline nlohmann::json gltf_vec3_json(const glm::vec3& v) {
    return nlohmann::json::array({v.x, v.y, v.z});
}

// glTF writes quaternions as x, y, z, w.
inline nlohmann::json gltf_quat_json(const glm::dquat& q) {
    return nlohmann::json::array({q.x, q.y, q.z, q.w});
}

// Adds `name` to the document's extensionsUsed once.
inline void add_extension_used(nlohmann::json& doc, const char* name) {
    if (!doc.contains("extensionsUsed") || !doc["extensionsUsed"].is_array()) {
        doc["extensionsUsed"] = nlohmann::json::array();
    }
    nlohmann::json& used = doc["extensionsUsed"];
    if (std::find(used.begin(), used.end(), name) == used.end()) used.push_back(name);
}

// Removes `name` from the list `list` ("extensionsUsed"), and the list when it empties.
inline void remove_extension_name(nlohmann::json& doc, const char* list, const char* name) {
    if (!doc.contains(list) || !doc[list].is_array()) return;
    nlohmann::json& names = doc[list];
    names.erase(std::remove(names.begin(), names.end(), nlohmann::json(name)), names.end());
    if (names.empty()) doc.erase(list);
}

}  // namespace lc::client

#include "editor_client/scene/gltf_light_reader.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "editor_client/scene/gltf_loader.h"
#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

// Stable for a given file: the light's index and name and where it hangs.
Guid guid_from_path(int light_index, std::string_view name, uint64_t path_hash) {
    const std::string tag = "KHR_lights_punctual/" + std::to_string(light_index) + "/" + std::string(name);
    std::vector<uint8_t> bytes(tag.begin(), tag.end());
    for (int i = 0; i < 8; ++i) bytes.push_back(uint8_t(path_hash >> (8 * i)));
    return Guid::from_bytes(bytes);
}

Result<LightType> light_type_of(std::string_view type) {
    if (type == "point") return LightType::kPoint;
    if (type == "spot") return LightType::kSpot;
    if (type == "directional") return LightType::kDirectional;
    return make_error("has unknown type '" + std::string(type) + "' (expected point, spot or directional)");
}

}  // namespace

Result<SceneLight> GltfLightReader::read(int node_index, const glm::dmat4& world, uint64_t path_hash) const {
    const std::string node_what = "node " + std::to_string(node_index);
    const GltfNode& node = table_.nodes[size_t(node_index)];
    Result<int> light_index = light_index_of(node, node_what);
    if (!light_index) return light_index.failure();
    const GltfPunctualLight& in = table_.lights[size_t(*light_index)];
    const std::string_view name = table_.string(in.name);
    const std::string what =
        "light " + std::to_string(*light_index) + (name.empty() ? "" : " '" + std::string(name) + "'");

    SceneLight light;
    LC_RETURN_IF_ERROR(read_emission(in, what, light));
    LC_RETURN_IF_ERROR(place(world, node_what, what, light));
    // The node's flag is read (and warned about) only when the light's is not set.
    light.classic = classic_flag(in.classic, what) || classic_flag(node.classic, node_what);
    if (node.guid_extras == GltfNode::GuidExtras::kInvalid) {
        return diagnostics_.fail(node_what + ": extras." + kGuidExtrasKey + " is not a GUID");
    }
    light.guid = node.guid_extras == GltfNode::GuidExtras::kGuid
                     ? node.guid
                     : guid_from_path(*light_index, name, path_hash);
    return light;
}

// An `extras.lightcuts_classic` flag; other types than boolean are ignored with a warning.
bool GltfLightReader::classic_flag(ExtrasFlag flag, const std::string& what) const {
    if (flag == ExtrasFlag::kNotBoolean) {
        diagnostics_.warn(what + ": extras." + kClassicExtrasKey + " is not a boolean; ignored");
    }
    return flag == ExtrasFlag::kTrue;
}

// The index of the punctual light a node names, checked against the file's lights.
Result<int> GltfLightReader::light_index_of(const GltfNode& node, const std::string& node_what) const {
    if (node.light != LightReference::kNumber) {
        return diagnostics_.fail(node_what + ": KHR_lights_punctual extension has no 'light' index");
    }
    const double number = node.light_number;
    if (!(number >= 0.0) || number >= double(table_.lights.size()) || number != std::floor(number)) {
        const bool integral = number == std::floor(number) && std::abs(number) < 1e15;
        return diagnostics_.fail(node_what + " uses light " +
                                 (integral ? std::to_string(int64_t(number)) : message_number(number)) +
                                 ", which does not exist (the file has " +
                                 std::to_string(table_.lights.size()) + " lights)");
    }
    return static_cast<int>(number);
}

// Type, colour, intensity, range and spot cone, each checked.
Status GltfLightReader::read_emission(const GltfPunctualLight& in, const std::string& what,
                                      SceneLight& light) const {
    Result<LightType> type = light_type_of(table_.string(in.type));
    if (!type) return diagnostics_.fail(what + " " + type.error());
    light.type = *type;
    if (in.color_count != 0) {
        if (in.color_count != 3) return diagnostics_.fail(what + ": 'color' needs 3 numbers");
        for (double c : in.color) {
            if (!std::isfinite(c) || c < 0.0) {
                return diagnostics_.fail(what + ": 'color' components must be finite and >= 0");
            }
        }
        light.color = glm::vec3(float(in.color[0]), float(in.color[1]), float(in.color[2]));
    }
    if (!std::isfinite(in.intensity)) return diagnostics_.fail(what + ": intensity is not finite");
    if (in.intensity < 0.0)
        return diagnostics_.fail(what + ": negative intensity " + message_number(in.intensity));
    if (in.intensity > double(std::numeric_limits<float>::max())) {
        return diagnostics_.fail(what + ": intensity " + message_number(in.intensity) + " overflows a float");
    }
    light.intensity = float(in.intensity);
    if (!std::isfinite(in.range) || in.range < 0.0) {
        return diagnostics_.fail(what + ": range must be finite and > 0 (absent means unbounded)");
    }
    light.range = float(in.range);
    if (light.type == LightType::kSpot) return read_spot_cone(in, what, light);
    return Ok{};
}

Status GltfLightReader::read_spot_cone(const GltfPunctualLight& in, const std::string& what,
                                       SceneLight& light) const {
    const double inner = in.inner_cone_angle;
    const double outer = in.outer_cone_angle;
    if (!std::isfinite(inner) || !std::isfinite(outer) || inner < 0.0 || outer > std::numbers::pi / 2.0 ||
        !(inner < outer)) {
        return diagnostics_.fail(what + ": invalid spot angles (inner " + message_number(inner) + ", outer " +
                                 message_number(outer) + "); need 0 <= inner < outer <= pi/2");
    }
    light.inner_cone_angle = float(inner);
    light.outer_cone_angle = float(outer);
    // Float rounding must not break inner < outer.
    if (!(light.inner_cone_angle < light.outer_cone_angle)) {
        return diagnostics_.fail(what + ": spot angles too close to tell apart in float precision");
    }
    return Ok{};
}

// The node's transform gives the light its position and its direction (-z).
Status GltfLightReader::place(const glm::dmat4& world, const std::string& node_what, const std::string& what,
                              SceneLight& light) const {
    light.position = glm::vec3(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    if (!std::isfinite(light.position.x) || !std::isfinite(light.position.y) ||
        !std::isfinite(light.position.z)) {
        return diagnostics_.fail(node_what + ": the position of " + what + " is not finite");
    }
    const glm::dvec3 direction = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
    const double length = glm::length(direction);
    if (length > 1e-12 && std::isfinite(length)) {
        light.direction = glm::vec3(direction / length);
    } else if (light.type != LightType::kPoint) {
        return diagnostics_.fail(node_what + ": the transform of " + what +
                                 " collapses its direction (zero scale)");
    }
    return Ok{};
}

// Sorted (GUID, index) pairs rather than a map: a million lights. The pair
// named is the one a scan in light order meets first: the smallest second
// index of any shared GUID, with that GUID's first index.
Status check_unique_light_guids(std::span<const SceneLight> lights, const GltfDiagnostics& diagnostics) {
    std::vector<std::pair<Guid, uint32_t>> order(lights.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = {lights[i].guid, uint32_t(i)};
    std::sort(order.begin(), order.end());
    size_t first = 0;
    size_t second = std::numeric_limits<size_t>::max();
    for (size_t k = 1; k < order.size(); ++k) {
        if (order[k].first == order[k - 1].first && order[k].second < second &&
            (k < 2 || order[k - 2].first != order[k].first)) {
            first = order[k - 1].second;
            second = order[k].second;
        }
    }
    if (second == std::numeric_limits<size_t>::max()) return Ok{};
    return diagnostics.fail("lights " + std::to_string(first) + " and " + std::to_string(second) +
                            " share GUID " + lights[second].guid.to_hex());
}

}  // namespace lc::client

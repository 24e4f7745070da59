#pragma once
// The light as the scene describes it (glTF KHR_lights_punctual semantics).
// Shared by the client (which reads it from glTF) and the server (which
// receives it on the scene channel).
#include <glm/vec3.hpp>

#include <cstdint>
#include <limits>
#include <numbers>

#include "lightcuts/guid.h"

namespace lc {

// kOriented: the paper's oriented light, a point of an area light. It emits
// intensity x max(0, cos) of the angle to its normal `direction` (a cosine
// emitter), so its total power is pi x intensity per channel.
enum class LightType : uint8_t { kPoint = 0, kSpot = 1, kDirectional = 2, kOriented = 3 };
inline constexpr int kLightTypeCount = 4;

const char* light_type_name(LightType type);

struct SceneLight {
    Guid guid;
    LightType type = LightType::kPoint;
    // A VPL (indirect, not a patch): the bounce that left it, 1 and up; 0 for
    // every other light, and for VPLs of servers that did not record it. In
    // the padding after `type`: 2^20 lights are not made larger.
    uint16_t bounce = 0;
    glm::vec3 position{0.0f};
    // Direction the light shines along (spot, directional) or the emitting
    // side's normal (oriented); unit length.
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    // Linear RGB, each component >= 0.
    glm::vec3 color{1.0f};
    // Candela for point and spot lights (oriented: along the normal), lux for
    // directional lights.
    float intensity = 1.0f;
    // Distance at which the light is windowed to zero; 0 means unbounded.
    float range = 0.0f;
    // Spot cone angles in radians, 0 <= inner < outer <= pi/2.
    float inner_cone_angle = 0.0f;
    float outer_cone_angle = std::numbers::pi_v<float> / 4.0f;
    // Classic lights stay out of the tree and are shaded per light.
    bool classic = false;
    // Bounced light the server's indirect stage made (a VPL or a radiosity
    // patch): clamped by the renderer, skipped by render --indirect off. Never
    // on the scene channel: only the server sets it.
    bool indirect = false;
    // An indirect light that is a radiosity patch, not a VPL: a large emitter
    // the renderer evaluates as a disk of `source_radius` (sqrt(area / pi))
    // instead of clamping it. Only the server sets it, with `indirect`.
    bool patch = false;
    float source_radius = 0.0f;
};

// The server holds one per light (2^20 and more): a new field goes in padding.
static_assert(sizeof(SceneLight) == 80);

// The deepest bounce a light can record (SceneLight::bounce, LightTreeNode::bounce,
// FLightData.light_source_length): deeper VPL requests are refused, not truncated.
inline constexpr uint32_t kMaxRecordedBounce = std::numeric_limits<decltype(SceneLight::bounce)>::max();

}  // namespace lc

#pragma once
// Mouse orbit around a target: left drag turns (yaw about +Y, pitch clamped
// short of the poles), right drag pans, the wheel dollies.
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "editor_client/render/render_settings.h"

namespace lc::client {

class OrbitCamera {
public:
    explicit OrbitCamera(const RenderCamera& start);

    void orbit(glm::vec2 drag_pixels);
    void pan(glm::vec2 drag_pixels);
    void dolly(float wheel_steps);
    RenderCamera camera() const;

private:
    glm::vec3 target_;
    float distance_;
    float yaw_;    // radians about +Y, 0 looking down -Z
    float pitch_;  // radians, positive looking down on the target
    float yfov_;
};

}  // namespace lc::client

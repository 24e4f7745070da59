#pragma once
// Mouse orbit around a target: left drag turns (yaw about +Y, pitch clamped
// short of the poles), right drag pans, the wheel dollies. Fly controls move
// eye and target together along the view's axes, and look turns the view
// about the eye (the target swings round it).
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "editor_client/render/settings/render_settings.h"

namespace lc::client {

class OrbitCamera {
public:
    explicit OrbitCamera(const RenderCamera& start);

    void orbit(glm::vec2 drag_pixels);
    void pan(glm::vec2 drag_pixels);
    void dolly(float wheel_steps);
    // axes: x right, y world up, z forward (the view direction); distance in scene units.
    void fly(glm::vec3 axes, float distance);
    void look(glm::vec2 drag_pixels);
    // The fly speed the editor uses: half the orbit distance per second (at
    // least 0.5 units), so small and large scenes cross in similar times.
    float fly_speed() const;
    RenderCamera camera() const;

private:
    glm::vec3 target_;
    float distance_;
    float yaw_;    // radians about +Y, 0 looking down -Z
    float pitch_;  // radians, positive looking down on the target
    float yfov_;
};

}  // namespace lc::client

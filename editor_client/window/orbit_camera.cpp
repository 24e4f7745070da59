#include "editor_client/window/orbit_camera.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>

namespace lc::client {
namespace {

constexpr float kRadiansPerPixel = 0.005f;
constexpr float kMaxPitch = 1.55f;  // just short of straight up/down, where yaw is undefined

}  // namespace

OrbitCamera::OrbitCamera(const RenderCamera& start) : target_(start.target), yfov_(start.yfov) {
    glm::vec3 offset = start.eye - start.target;
    distance_ = std::max(glm::length(offset), 1e-4f);
    glm::vec3 dir = offset / distance_;
    pitch_ = std::asin(std::clamp(dir.y, -1.0f, 1.0f));
    yaw_ = std::atan2(dir.x, dir.z);
}

void OrbitCamera::orbit(glm::vec2 drag) {
    yaw_ -= drag.x * kRadiansPerPixel;
    pitch_ = std::clamp(pitch_ + drag.y * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(glm::vec2 drag) {
    RenderCamera c = camera();
    glm::vec3 forward = glm::normalize(c.target - c.eye);
    glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    glm::vec3 up = glm::cross(right, forward);
    // One pixel moves the target by about one pixel's footprint at the target.
    float scale = distance_ * 2.0f * std::tan(0.5f * yfov_) / 600.0f;
    target_ += (-drag.x * right + drag.y * up) * scale;
}

void OrbitCamera::fly(glm::vec3 axes, float distance) {
    if (!(distance > 0.0f) || axes == glm::vec3(0.0f)) return;
    RenderCamera c = camera();
    glm::vec3 forward = glm::normalize(c.target - c.eye);
    glm::vec3 right = glm::normalize(glm::cross(forward, glm::vec3(0, 1, 0)));
    glm::vec3 step = axes.x * right + axes.y * glm::vec3(0, 1, 0) + axes.z * forward;
    const float length = glm::length(step);
    if (length > 0.0f) target_ += step / length * distance;
}

void OrbitCamera::look(glm::vec2 drag) {
    const glm::vec3 eye = camera().eye;
    yaw_ -= drag.x * kRadiansPerPixel;
    pitch_ = std::clamp(pitch_ - drag.y * kRadiansPerPixel, -kMaxPitch, kMaxPitch);
    glm::vec3 dir(std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_),
                  std::cos(pitch_) * std::cos(yaw_));
    target_ = eye - dir * distance_;
}

float OrbitCamera::fly_speed() const { return std::max(0.5f * distance_, 0.5f); }

void OrbitCamera::dolly(float steps) {
    distance_ = std::clamp(distance_ * std::pow(0.9f, steps), 1e-4f, 1e7f);
}

RenderCamera OrbitCamera::camera() const {
    RenderCamera c;
    glm::vec3 dir(std::cos(pitch_) * std::sin(yaw_), std::sin(pitch_),
                  std::cos(pitch_) * std::cos(yaw_));
    c.target = target_;
    c.eye = target_ + dir * distance_;
    c.up = {0.0f, 1.0f, 0.0f};
    c.yfov = yfov_;
    return c;
}

}  // namespace lc::client

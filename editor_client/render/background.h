#pragma once
// What the lighting passes show where no geometry is hit
// (shaders/background.glsl): the environment in its GPU form, uploaded once,
// and each frame's eye rays, rebuilt from the camera the G-buffer used.
#include <glm/vec3.hpp>

#include <cstdint>
#include <vector>

#include "editor_client/render/settings/render_settings.h"
#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/environment.h"

namespace lc::client {

// The frame's background: the environment's parameters (null: black) and the
// eye rays of a width x height frame rendered with `settings` over the scene
// bounds (the G-buffer's projection, jitter and corner grid included).
GpuBackground make_gpu_background(const Environment* environment, const RenderSettings& settings,
                                  uint32_t width, uint32_t height, const glm::vec3& bounds_min,
                                  const glm::vec3& bounds_max);

// The CPU's side of shaders/background.glsl, for the supersampled CPU
// methods: the eye ray through image position (x, y) (pixel centres at
// + 0.5) of the frame `background` was made for, and the environment's
// radiance along a unit direction.
glm::dvec3 background_eye_ray(const GpuBackground& background, double x, double y);
glm::dvec3 environment_radiance(const Environment& environment, const glm::dvec3& direction);

}  // namespace lc::client

#pragma once
// The shadow ray from a shading point towards a light, built the same way on
// the CPU (here, in double) and on the GPU (shaders/shadow_rays.glsl, float)
// by device/shadow_segment.glsl.h: it starts `bias` along the unit normal and
// `bias` along itself, so it hits neither the surface it leaves nor one it
// meets in a crease, and ends `bias` short of a positional light (a light on a
// surface is not hidden by that surface); towards a directional light it runs
// to kShadowRayFar.
#include <glm/vec3.hpp>

#include <cstdint>
#include <string>
#include <string_view>

#include "lightcuts/name_table.h"
#include "lightcuts/occlusion/shadow_bvh.h"
#include "lightcuts/scene.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"

namespace lc {

inline constexpr double kShadowRayFar = 1e30;

// What the user asked for: auto lets the scene analysis decide.
enum class ShadowMode : uint8_t { kAuto = 0, kOn = 1, kOff = 2 };
inline constexpr NameTable<ShadowMode, 3> kShadowModeNames{{
    {"auto", ShadowMode::kAuto},
    {"on", ShadowMode::kOn},
    {"off", ShadowMode::kOff},
}};
Result<ShadowMode> parse_shadow_mode(std::string_view text);
const char* shadow_mode_name(ShadowMode mode);

// 1e-4 of the scene's extent, plus enough float ulps of its largest
// coordinate that a float position rounded onto a surface still clears it.
float shadow_ray_bias(const Scene& scene);

// V in {0, 1}: 1 when nothing in `occluders` lies between x (unit normal n)
// and the light at `position` (or, for a directional light, towards
// -direction).
double light_visibility(const ShadowBvh& occluders, double bias, LightType type,
                        const glm::dvec3& position, const glm::dvec3& direction,
                        const glm::dvec3& x, const glm::dvec3& n);

}  // namespace lc

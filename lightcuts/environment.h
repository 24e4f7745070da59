#pragma once
// Light from the sky as a scene describes it: an equirectangular HDR map or a
// Preetham sun and sky (one or the other), scaled and turned. The client
// loads it, the env channel carries it, the server samples it into
// directional lights (lightmass_server/emitters/environment_sampler.h).
#include <cstdint>
#include <optional>

#include "lightcuts/equirect_map.h"
#include "lightcuts/preetham_sky.h"

namespace lc {

// Directional lights an environment becomes (--environment-lights). 3,000 is
// the paper's budget for an HDR map; a sun and sky shares it in the paper's
// 64 : 5,000 ratio (38 sun and 2,962 sky lights).
inline constexpr uint32_t kDefaultEnvironmentLights = 3000;
inline constexpr uint32_t kMaxEnvironmentLights = 1u << 22;  // 4,194,304

struct Environment {
    EquirectMap map;                  // empty for a sun and sky
    std::optional<SkyParameters> sky;  // set for a sun and sky
    float intensity = 1.0f;           // scales the radiance, >= 0
    float rotation_deg = 0.0f;        // turns the map about +Y

    bool has_map() const { return !map.empty(); }
    bool has_sky() const { return sky.has_value(); }
};

// count in [1, kMaxEnvironmentLights] (2 at least for a sun and sky: one for
// the sun, one for the sky); the message names the bounds.
Status validate_environment_light_count(const Environment& environment, uint32_t count);

}  // namespace lc

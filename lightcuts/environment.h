#pragma once
// Light from the sky as a scene describes it: an equirectangular HDR map or a
// Preetham sun and sky (one or the other), scaled and turned. The client
// loads it, the env channel carries it, the server samples it into
// directional lights (lightmass_server/emitters/environment_sampler.h).
#include <optional>

#include "lightcuts/equirect_map.h"
#include "lightcuts/preetham_sky.h"

namespace lc {

struct Environment {
    EquirectMap map;                  // empty for a sun and sky
    std::optional<SkyParameters> sky;  // set for a sun and sky
    float intensity = 1.0f;           // scales the radiance, >= 0
    float rotation_deg = 0.0f;        // turns the map about +Y

    bool has_map() const { return !map.empty(); }
    bool has_sky() const { return sky.has_value(); }
};

}  // namespace lc

#include "lightcuts/environment.h"

#include <string>

namespace lc {

Status validate_environment_light_count(const Environment& environment, uint32_t count) {
    const uint32_t least = environment.has_sky() ? 2 : 1;
    if (count < least || count > kMaxEnvironmentLights)
        return make_error("environment lights: " + std::to_string(count) + " is outside [" + std::to_string(least) +
                          ", " + std::to_string(kMaxEnvironmentLights) + "]" +
                          (environment.has_sky() ? " (a sun and sky needs a sun light and a sky light)" : ""));
    return Ok{};
}

}  // namespace lc

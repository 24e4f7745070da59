#include "protocol/bake_limits.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace lc {
namespace {

Status out_of_range(const std::string& setting, const std::string& value, const std::string& range) {
    return make_error(setting + " " + value + " is out of range: it must be " + range);
}

Status validate_indirect(const IndirectRequest& indirect) {
    if (indirect.method == IndirectMethod::kOff) return Ok{};
    if (indirect.method == IndirectMethod::kVpl) {
        if (indirect.bounces < 1 || indirect.bounces > kMaxBakeBounces)
            return out_of_range("vpl bounces", std::to_string(indirect.bounces),
                                "1 to " + std::to_string(kMaxBakeBounces));
        if (indirect.vpl_count < 1 || indirect.vpl_count > kMaxVplPaths)
            return out_of_range("vpl count (light paths)", std::to_string(indirect.vpl_count),
                                "1 to " + std::to_string(kMaxVplPaths));
        return Ok{};
    }
    if (indirect.method != IndirectMethod::kRadiosity)
        return make_error("unknown indirect method " + std::to_string(int(indirect.method)));
    const float patch = indirect.patch_size;
    if (!std::isfinite(patch) || patch < kMinPatchSize || patch > kMaxPatchSize)
        return out_of_range(
            "radiosity patch size", readable_number(patch),
            readable_number(kMinPatchSize) + " to " + readable_number(kMaxPatchSize) + " scene units");
    const double tolerance = indirect.tolerance;
    if (!std::isfinite(tolerance) || tolerance < 0.0 || tolerance >= 1.0)
        return out_of_range("radiosity tolerance", readable_number(tolerance), "in [0, 1)");
    return Ok{};
}

}  // namespace

std::string readable_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

uint64_t vpl_light_reservation(uint64_t paths, uint32_t bounces, double max_albedo) {
    const double survival = std::clamp(max_albedo, 0.0, kVplMaxSurvival);
    const double per_path = std::min(double(bounces), std::ceil(2.0 / (1.0 - survival)));
    const double lights = double(paths) * per_path;
    return lights >= double(kMaxIndirectLights) ? kMaxIndirectLights : uint64_t(lights);
}

Status validate_bake_settings(const BakeRequestMsg& request) {
    if (request.area_lights > kMaxAreaLights)
        return out_of_range("area-light samples", std::to_string(request.area_lights),
                            "0 (the default) to " + std::to_string(kMaxAreaLights));
    if (request.environment_lights > kMaxBakeEnvironmentLights)
        return out_of_range("environment lights", std::to_string(request.environment_lights),
                            "0 (the default) to " + std::to_string(kMaxBakeEnvironmentLights));
    return validate_indirect(request.indirect);
}

}  // namespace lc

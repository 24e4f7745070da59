#include "editor_client/commands/environment_flags.h"

#include "editor_client/scene/inputs/environment_image.h"
#include "lightcuts/status_macros.h"
#include "protocol/environment_records.h"

namespace lc::client {

void EnvironmentFlags::add_to(CLI::App& cmd) {
    auto* file_opt = cmd.add_option("--environment", file, "Equirectangular Radiance .hdr lighting the scene");
    auto* sky_opt = cmd.add_option("--sky", sky, "Preetham sun and sky: ELEVATION,AZIMUTH,TURBIDITY (degrees)");
    file_opt->excludes(sky_opt);
    cmd.add_option("--environment-intensity", intensity, "Scale of the environment's radiance")->capture_default_str();
    cmd.add_option("--environment-rotation", rotation_deg, "Turn the environment map about +Y (degrees)")
        ->capture_default_str();
    cmd.add_option("--environment-lights", lights,
                   "Directional lights the environment becomes (default " +
                       std::to_string(kDefaultEnvironmentLights) + ", at most " +
                       std::to_string(kMaxEnvironmentLights) + ")");
}

Result<std::shared_ptr<const Environment>> EnvironmentFlags::load(std::shared_ptr<const Environment> named) const {
    if (!requested()) {
        if (lights && !named)
            return make_error("--environment-lights needs --environment or --sky (or an environment in the glTF)");
        if (lights) {
            Status count = validate_environment_light_count(*named, *lights);
            if (!count) return make_error("--" + count.error());
        }
        return named;
    }
    auto environment = std::make_shared<Environment>();
    environment->intensity = intensity;
    environment->rotation_deg = rotation_deg;
    if (!sky.empty()) {
        Result<SkyParameters> parsed = parse_sky_parameters(sky);
        if (!parsed) return parsed.failure();
        environment->sky = *parsed;
    } else {
        Result<EquirectMap> map = load_environment_image(file);
        if (!map) return map.failure();
        environment->map = std::move(map.value());
    }
    LC_RETURN_IF_ERROR(validate_environment(*environment));
    if (lights) {
        Status count = validate_environment_light_count(*environment, *lights);
        if (!count) return make_error("--" + count.error());
    }
    return std::shared_ptr<const Environment>(std::move(environment));
}

}  // namespace lc::client

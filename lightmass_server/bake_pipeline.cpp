#include "lightmass_server/bake_pipeline.h"

#include <optional>
#include <span>
#include <string>

#include "lightmass_server/emitters/area_light_sampler.h"
#include "lightmass_server/emitters/environment_sampler.h"
#include "lightmass_server/raycast/ray_caster.h"

namespace lc::bake {

Result<BuildResult> run_bake(const BakeInputs& inputs, const ProgressFn& progress) {
    auto report = [&](const std::string& stage, double percent) {
        return !progress || progress(stage, percent);
    };
    std::vector<std::string> effects;
    std::vector<std::string> warnings;
    std::span<const SceneLight> lights = *inputs.lights;
    std::vector<SceneLight> with_area_lights;
    std::optional<RayCaster> caster;
    if (inputs.geometry) {
        if (!report("ray caster", 0.0)) return make_error("cancelled", ErrorKind::kCancelled);
        Result<RayCaster> built = RayCaster::build(*inputs.geometry, inputs.raycast_threads);
        if (!built) return make_error("ray caster: " + built.error());
        caster.emplace(std::move(built.value()));

        if (!report("area lights", 0.0)) return make_error("cancelled", ErrorKind::kCancelled);
        Result<AreaLightSampling> sampled =
            sample_area_lights(*inputs.geometry, inputs.area_lights, inputs.build.seed);
        if (!sampled) return make_error("area lights: " + sampled.error());
        if (sampled->budget_raised) {
            warnings.push_back("--area-lights " + std::to_string(inputs.area_lights) + " is below the " +
                               std::to_string(sampled->emissive_triangles) +
                               " emissive triangles: one sample each");
        }
        if (!sampled->lights.empty()) {
            effects.push_back("area lights: simulated (" +
                              std::to_string(sampled->emissive_triangles) + " emissive triangles, " +
                              std::to_string(sampled->lights.size()) + " samples)");
            with_area_lights.assign(lights.begin(), lights.end());
            with_area_lights.insert(with_area_lights.end(), sampled->lights.begin(),
                                    sampled->lights.end());
            lights = with_area_lights;
        }
    }
    if (effects.empty()) effects.push_back("area lights: skipped: no drawn triangle emits power");
    if (!report(effects.back(), 0.0)) return make_error("cancelled", ErrorKind::kCancelled);

    std::vector<SceneLight> with_environment;
    if (inputs.environment) {
        if (!report("sampling environment", 0.0)) return make_error("cancelled", ErrorKind::kCancelled);
        Result<EnvironmentLights> sampled =
            sample_environment(*inputs.environment, inputs.environment_lights, inputs.build.seed);
        if (!sampled) return sampled.failure();
        effects.push_back(sampled->census);
        if (!report(sampled->census, 0.0)) return make_error("cancelled", ErrorKind::kCancelled);
        with_environment.assign(lights.begin(), lights.end());
        with_environment.insert(with_environment.end(), sampled->lights.begin(), sampled->lights.end());
        lights = with_environment;
    }

    Result<BuildResult> built = build_light_tree(lights, inputs.build, progress);
    if (!built) return built;
    built->report.effects = std::move(effects);
    built->report.warnings.insert(built->report.warnings.begin(), warnings.begin(), warnings.end());
    return built;
}

}  // namespace lc::bake

#include "lightmass_server/indirect/indirect_stage.h"

#include <algorithm>
#include <cstdio>
#include <string>

#include "lightcuts/guid.h"

namespace lc::bake {

IndirectOptions indirect_options(const IndirectRequest& request, uint64_t seed) {
    IndirectOptions options;
    options.method = request.method;
    options.vpl.bounces = request.bounces;
    options.vpl.particle_count = request.vpl_count;
    options.vpl.seed = seed;
    options.radiosity.patch_size = request.patch_size;
    options.radiosity.tolerance = request.tolerance;
    return options;
}

std::vector<SceneLight> as_tree_lights(std::span<const IndirectLight> lights, uint64_t first_index) {
    std::vector<SceneLight> out;
    out.reserve(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) {
        const IndirectLight& bounced = lights[i];
        glm::vec3 intensity = intensity_along_normal(bounced);
        float scale = std::max({intensity.x, intensity.y, intensity.z});
        if (!(scale > 0.0f)) continue;
        const uint64_t index = first_index + i;
        uint8_t bytes[12] = {'i', 'n', 'd', 'i'};
        for (int b = 0; b < 8; ++b) bytes[4 + b] = uint8_t(index >> (8 * b));
        SceneLight light;
        light.guid = Guid::from_bytes(bytes);
        light.type = LightType::kOriented;
        light.position = bounced.position;
        light.direction = bounced.normal;
        light.color = intensity / scale;
        light.intensity = scale;
        light.indirect = true;
        light.patch = bounced.patch_radius > 0.0f;
        light.source_radius = bounced.patch_radius;
        // trace_vpls refuses requests deeper than SceneLight::bounce holds.
        light.bounce = static_cast<uint16_t>(bounced.bounce);
        out.push_back(light);
    }
    return out;
}

// "3 bounces" for a cap; for the default, every bounce, the deepest one a path reached.
static std::string bounces_text(const VplOptions& options, const std::vector<IndirectLight>& lights) {
    if (options.bounces < kMaxVplBounces) return std::to_string(options.bounces) + " bounces";
    uint32_t deepest = 0;
    for (const IndirectLight& l : lights) deepest = std::max(deepest, l.bounce);
    return "all bounces until Russian roulette, the deepest " + std::to_string(deepest);
}

Result<IndirectStageResult> run_indirect_stage(const SceneGeometry& geometry, const RayCaster* caster,
                                               std::span<const SceneLight> lights, const IndirectOptions& options,
                                               const ProgressFn& progress) {
    IndirectStageResult stage;
    bool no_bounce = options.method == IndirectMethod::kOff ||
                     (options.method == IndirectMethod::kVpl && options.vpl.bounces == 0);
    if (no_bounce) {
        stage.census = "skipped: no bounce requested";
        return stage;
    }
    if (caster == nullptr || caster->triangle_count() == 0) {
        stage.census = "skipped: the scene has no geometry";
        return stage;
    }
    char text[160];
    if (options.method == IndirectMethod::kVpl) {
        auto traced = trace_vpls(geometry, *caster, lights, options.vpl, progress);
        if (!traced.ok()) return traced.failure();
        stage.lights = std::move(traced->lights);
        std::snprintf(text, sizeof text, "simulated (%zu VPLs from %llu particles, %s)", stage.lights.size(),
                      static_cast<unsigned long long>(traced->particles), bounces_text(options.vpl, stage.lights).c_str());
        stage.census = text;
        return stage;
    }
    auto solved = solve_radiosity(geometry, *caster, lights, options.radiosity, progress);
    if (!solved.ok()) return solved.failure();
    stage.lights = std::move(solved->lights);
    std::snprintf(text, sizeof text, "simulated (%zu patches, all bounces, %llu steps, %.3g%% unshot)",
                  solved->mesh.patches.size(), static_cast<unsigned long long>(solved->steps),
                  100.0 * solved->unshot_fraction);
    stage.census = text;
    if (!solved->converged) stage.warnings.push_back(solved->message);
    stage.patches = std::move(solved->mesh.patches);
    stage.patch_radiosity = std::move(solved->radiosity);
    return stage;
}

}  // namespace lc::bake

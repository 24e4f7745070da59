#include "lightmass_server/bake/bake_pipeline.h"

#include <initializer_list>
#include <optional>
#include <span>
#include <string>

#include "lightmass_server/emitters/area_light_sampler.h"
#include "lightmass_server/emitters/environment_sampler.h"
#include "lightmass_server/indirect/radiosity_ply.h"
#include "lightmass_server/raycast/ray_caster.h"

namespace lc::bake {
namespace {

bool has_emissive_material(const SceneGeometry& geometry) {
    for (const SurfaceTriangle& t : geometry.triangles) {
        if (t.material >= geometry.materials.size()) continue;
        const glm::vec3 e = geometry.materials[t.material].emission;
        if (e.x + e.y + e.z > 0.0f) return true;
    }
    return false;
}

// The emissive triangles as oriented lights after the scene's, into `added`
// (left empty when no triangle emits), with their census line. The scene's
// lights are copied in front only when a triangle may emit.
Status add_area_lights(const BakeInputs& inputs, std::vector<SceneLight>& added,
                       std::vector<std::string>& effects, std::vector<std::string>& warnings) {
    // No triangle emits without an emissive material, so then no sample needs the scene's lights before it.
    std::vector<SceneLight> scene;
    if (has_emissive_material(*inputs.geometry)) scene = *inputs.lights;
    const size_t scene_count = scene.size();
    Result<AreaLightSampling> sampled =
        sample_area_lights(*inputs.geometry, inputs.area_lights, inputs.build.seed, IndexRange{},
                           inputs.stop.get(), std::move(scene));
    if (!sampled && sampled.error_kind() == ErrorKind::kCancelled) return sampled.failure();
    if (!sampled) return make_error("area lights: " + sampled.error());
    if (sampled->budget_raised) {
        warnings.push_back("--area-lights " + std::to_string(inputs.area_lights) + " is below the " +
                           std::to_string(sampled->emissive_triangles) +
                           " emissive triangles: one sample each");
    }
    const size_t samples = sampled->lights.size() - std::min(sampled->lights.size(), scene_count);
    if (sampled->emissive_triangles > 0 && samples > 0) {
        effects.push_back("area lights: simulated (" + std::to_string(sampled->emissive_triangles) +
                          " emissive triangles, " + std::to_string(samples) + " samples)");
        added = std::move(sampled->lights);
    }
    return Ok{};
}

// The tree of `lights`; the builders poll the stop through their progress
// callback (between levels and merge batches), the optimal-pair builder's
// approximate levels inside their loops too.
Result<BuildResult> build_stoppable(std::span<const SceneLight> lights, const BakeInputs& inputs,
                                    const ProgressFn& progress) {
    const BakeStop* stop = inputs.stop.get();
    const ProgressFn build_progress = [&](std::string_view stage, double percent) {
        return !stop_requested(stop) && (!progress || progress(stage, percent));
    };
    BuildOptions options = inputs.build;
    options.stop = stop;
    Result<BuildResult> built = build_light_tree(lights, options, build_progress);
    if (!built && built.error_kind() == ErrorKind::kCancelled && stop_requested(stop))
        return stop->reason("tree build");
    return built;
}

// The tree's input list: the scene's lights, then each part in order, each
// part emptied once copied; empty when no part holds a light (the scene's
// own list is used as it is). A lone part is moved, not copied. Copied in
// strides that ask the stop: 4 M area-light samples are 320 MiB whose copy,
// page faults included, ran 300 ms and more unpolled (a SIGTERM waited 430 ms).
Result<std::vector<SceneLight>> join_lights(const std::vector<SceneLight>& scene,
                                            std::initializer_list<std::vector<SceneLight>*> parts,
                                            const BakeStop* stop) {
    size_t total = scene.size(), holding = 0;
    std::vector<SceneLight>* lone = nullptr;
    for (std::vector<SceneLight>* part : parts) {
        total += part->size();
        if (!part->empty()) ++holding, lone = part;
    }
    if (holding == 0) return std::vector<SceneLight>{};
    if (holding == 1 && scene.empty()) return std::move(*lone);
    constexpr size_t kStride = size_t{1} << 16;
    StopPoll poll(stop);
    std::vector<SceneLight> all;
    all.reserve(total);
    auto append = [&](const std::vector<SceneLight>& from) {
        for (size_t begin = 0; begin < from.size(); begin += kStride) {
            if (poll.now()) return false;
            all.insert(all.end(), from.begin() + begin,
                       from.begin() + std::min(from.size(), begin + kStride));
        }
        return true;
    };
    if (!append(scene)) return stop->reason("joining the lights");
    for (std::vector<SceneLight>* part : parts) {
        if (!append(*part)) return stop->reason("joining the lights");
        std::vector<SceneLight>().swap(*part);
    }
    return all;
}

}  // namespace

Result<BuildResult> run_bake_in_process(const BakeInputs& inputs, const ProgressFn& progress) {
    if (inputs.ranks > 0) {
        return make_error("a bake over " + std::to_string(inputs.ranks) +
                              " ranks runs through run_bake (mpi/bake_dispatch.h), not in process",
                          ErrorKind::kFailed);
    }
    const BakeStop* stop = inputs.stop.get();
    auto report = [&](const std::string& stage, double percent) {
        return !stop_requested(stop) && (!progress || progress(stage, percent));
    };
    auto stopped = [&](const std::string& stage) {
        return stop ? stop->reason(stage) : make_error(stage + " cancelled", ErrorKind::kCancelled);
    };
    std::vector<std::string> effects;
    std::vector<std::string> warnings;
    // What the stages add to the scene's lights, in the tree's input order:
    // area samples, the sky's lights, the bounces. Copied beside the scene's
    // lights once, at the end, and only when there is any; the area samples
    // come after a copy of the scene's lights already.
    std::vector<SceneLight> added;
    std::optional<RayCaster> caster;
    if (inputs.geometry) {
        if (!report("ray caster", 0.0)) return stopped("ray caster");
        Result<RayCaster> built = RayCaster::build(*inputs.geometry, inputs.raycast_threads);
        if (!built) return make_error("ray caster: " + built.error());
        caster.emplace(std::move(built.value()));

        if (!report("area lights", 0.0)) return stopped("area lights");
        if (Status sampled = add_area_lights(inputs, added, effects, warnings); !sampled)
            return sampled.failure();
    }
    if (effects.empty()) effects.push_back("area lights: skipped: no drawn triangle emits power");
    if (!report(effects.back(), 0.0)) return stopped("area lights");
    TreeLightCounts counts;
    counts.punctual = inputs.lights->size();
    // The samples come after a copy of the scene's lights.
    counts.area_samples = added.empty() ? 0 : added.size() - inputs.lights->size();

    std::vector<SceneLight> environment_lights;
    if (inputs.environment) {
        if (!report("sampling environment", 0.0)) return stopped("environment sampling");
        Result<EnvironmentLights> sampled =
            sample_environment(*inputs.environment, inputs.environment_lights, inputs.build.seed, 0, 1, stop);
        if (!sampled) return sampled.failure();
        effects.push_back(sampled->census);
        if (!report(sampled->census, 0.0)) return stopped("environment sampling");
        environment_lights = std::move(sampled->lights);
    }

    // Photons leave the emissive triangles themselves, so the scene's own
    // lights and the sky's go in, not the area-light samples.
    std::vector<SceneLight> photon_sources;
    if (!environment_lights.empty() && inputs.indirect.method != IndirectMethod::kOff) {
        photon_sources = *inputs.lights;
        photon_sources.insert(photon_sources.end(), environment_lights.begin(), environment_lights.end());
    }
    const SceneGeometry no_geometry;
    IndirectOptions indirect_options = inputs.indirect;
    indirect_options.vpl.stop = indirect_options.radiosity.stop = stop;
    Result<IndirectStageResult> indirect = run_indirect_stage(
        inputs.geometry ? *inputs.geometry : no_geometry, caster ? &*caster : nullptr,
        photon_sources.empty() ? *inputs.lights : photon_sources, indirect_options, progress);
    if (!indirect) return indirect.failure();
    effects.push_back("indirect: " + indirect->census);
    if (!inputs.radiosity_out.empty() && !indirect->patches.empty()) {
        Status written = write_radiosity_ply(inputs.radiosity_out, indirect->patches, indirect->patch_radiosity);
        if (!written) warnings.push_back(written.error());
    }
    warnings.insert(warnings.end(), indirect->warnings.begin(), indirect->warnings.end());
    if (!report(effects.back(), 0.0)) return stopped("indirect light");
    std::vector<SceneLight> bounced = as_tree_lights(indirect->lights);
    counts.environment = environment_lights.size();
    counts.add_bounced(inputs.indirect.method, bounced.size());
    const std::vector<SceneLight> none;
    Result<std::vector<SceneLight>> all_lights =
        join_lights(added.empty() ? *inputs.lights : none, {&added, &environment_lights, &bounced}, stop);
    if (!all_lights) return all_lights.failure();
    Result<BuildResult> built =
        build_stoppable(all_lights->empty() ? *inputs.lights : *all_lights, inputs, progress);
    if (!built) return built;
    built->report.effects = std::move(effects);
    built->report.lights = counts;
    built->report.warnings.insert(built->report.warnings.begin(), warnings.begin(), warnings.end());
    return built;
}

}  // namespace lc::bake

#pragma once
// Inputs for the tests of bakes split over MPI ranks: a Cornell box bake with
// every sampler that splits (area lights, a sky, VPL paths), and scattered
// lights of two types with coincident positions for the LBVH.
#include <filesystem>
#include <memory>
#include <vector>

#include "indirect_scenes.h"
#include "lightcuts/seeded_mixer.h"
#include "lightmass_server/bake/bake_pipeline.h"

namespace lc::test {

using bake::BakeInputs;

// A Cornell box with its emissive panel, a few point lights, VPLs and area samples.
inline BakeInputs cornell_inputs() {
    BakeInputs inputs;
    auto lights = std::make_shared<std::vector<SceneLight>>();
    for (int i = 0; i < 8; ++i) {
        SceneLight light;
        light.guid = Guid{uint32_t(i + 1), 2, 3, 4};
        light.position = glm::vec3(0.2f + 0.08f * float(i), 0.8f, 0.3f + 0.05f * float(i));
        light.intensity = 0.5f + float(i);
        lights->push_back(light);
    }
    inputs.lights = lights;
    inputs.geometry = std::make_shared<SceneGeometry>(cornell_box().geometry);
    inputs.area_lights = 301;  // not a multiple of any rank count
    auto sky = std::make_shared<Environment>();
    sky->sky = SkyParameters{30.0f, 40.0f, 3.0f};
    sky->intensity = 1e-4f;
    inputs.environment = sky;
    inputs.environment_lights = 203;
    inputs.build.builder = BuilderKind::kLbvh;
    inputs.build.seed = 7;
    inputs.indirect.method = IndirectMethod::kVpl;
    inputs.indirect.vpl.particle_count = 3001;
    inputs.indirect.vpl.bounces = 3;
    inputs.indirect.vpl.seed = 7;
    inputs.mpi.launcher_args = {"--oversubscribe", "--allow-run-as-root", "--mca", "btl", "self,tcp",
                                "--bind-to", "none"};
    inputs.mpi.rank_program = std::filesystem::path(LC_BIN_DIR) / "lightmass_rank";
    return inputs;
}

// Lights with coincident positions (equal Morton codes) and two types.
inline std::vector<SceneLight> scattered_lights(size_t count) {
    std::vector<SceneLight> lights(count);
    SplitMix64 random(11);
    for (size_t i = 0; i < count; ++i) {
        lights[i].guid = Guid{uint32_t(i), 7, 7, 7};
        lights[i].type = i % 5 == 0 ? LightType::kSpot : LightType::kPoint;
        lights[i].position = i % 97 == 0
                                 ? glm::vec3(1.0f)
                                 : glm::vec3(random.uniform(), random.uniform(), random.uniform()) * 10.0f;
        lights[i].intensity = float(0.1 + random.uniform());
    }
    return lights;
}

}  // namespace lc::test

#pragma once
// An environment map or a Preetham sun and sky as directional lights of the
// tree (the Lightcuts paper, section 3: HDR environments and sun/sky).
//
// Stratified importance sampling with luminance-proportional strata: the
// map's texel rectangle is split along its longer side (in angle) where the
// luminous power divides as the lights do (half each), until a stratum holds
// one light, so every stratum carries the same power. A stratum's light shines from a direction drawn
// inside it with probability proportional to radiance times solid angle, and
// its irradiance (lux) is the stratum's exact solid-angle integral of
// radiance, so the lights' irradiances sum to the environment's integral
// (a uniform environment of radiance L gives pi L on an upward floor).
// The sun is a disc of uniform radiance sampled by its own lights, evenly
// spaced over the disc; the sky is rasterised and sampled as a map.
// Deterministic for a seed; the sampling runs on one thread.
#include <cstdint>
#include <string>
#include <vector>

#include "lightcuts/environment.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"
#include "lightmass_server/control/bake_stop.h"
#include "lightmass_server/builders/index_range.h"

namespace lc::bake {

// The sky is sampled from this raster (texel centres) of the model.
inline constexpr uint32_t kSkyRasterWidth = 1024;
inline constexpr uint32_t kSkyRasterHeight = 512;
// The paper's 64 sun lights for 5,000 sky lights.
inline constexpr double kSunShareOfSkyLights = 64.0 / 5064.0;

struct EnvironmentLights {
    std::vector<SceneLight> lights;
    // "environment: simulated (W x H map, N lights)" or "sun and sky: simulated (...)".
    std::string census;
};

// `environment` must be valid (protocol/environment_records.h); count 0 means the default.
// `part` of `parts` (an MPI rank's share): the map's or sky's light slots in
// share_of(...) and, for part 0, the sun's disc; the parts' lights, concatenated
// in part order, are the whole run's. Polls `stop` every row of the map and
// every stratum (null: never stops).
Result<EnvironmentLights> sample_environment(const Environment& environment, uint32_t count, uint64_t seed,
                                             uint32_t part = 0, uint32_t parts = 1,
                                             const BakeStop* stop = nullptr);

// The map's lights alone: `count` strata (fewer where a stratum has no power);
// a partial list when `stop` asked to stop.
// Light slot i (in output order, gaps where strata had no power) draws from
// its own stream (seed, i); `slots` makes only those (an MPI rank's share).
std::vector<SceneLight> sample_equirect_map(const EquirectMap& map, double rotation, double intensity,
                                            uint32_t count, uint64_t seed, IndexRange slots = {},
                                            const BakeStop* stop = nullptr);
// The sun's disc: `count` lights of equal irradiance summing to the disc's.
std::vector<SceneLight> sample_sun_disc(const SkyParameters& sky, double intensity, uint32_t count, uint64_t seed);

}  // namespace lc::bake

#pragma once
// Area lights from emissive triangles (the paper's Sec. 3: an area light
// becomes oriented point lights). A Lambertian emitter of radiance L and area
// A emits pi x L x A per channel; each emissive triangle gets a share of the
// sample budget proportional to that power (largest remainders, then at
// least one each), its samples stratified over it, each an oriented light (a cosine
// emitter facing the emitting side) of intensity power / (pi x count), so the
// samples' intensities sum to the triangle's power exactly (to float rounding).
#include <cstdint>
#include <vector>

#include "lightcuts/result.h"
#include "lightcuts/scene_geometry.h"
#include "lightcuts/scene_light.h"
#include "lightmass_server/control/bake_stop.h"
#include "lightmass_server/builders/index_range.h"

namespace lc::bake {

struct AreaLightSampling {
    std::vector<SceneLight> lights;  // oriented, triangle by triangle in geometry order
    size_t emissive_triangles = 0;   // non-degenerate triangles with emission > 0
    // The budget is raised to one sample per emissive triangle when smaller.
    bool budget_raised = false;
};

// Deterministic for equal geometry, budget and seed. `budget` >= 1.
// `samples`: which samples to make, by their index in the whole run's output
// (an MPI rank's share; each triangle's draws depend only on the seed and the
// triangle, so the shares concatenated are the whole run's lights). Polls
// `stop` every sample made (null: never stops). `before`: lights the samples
// follow in `lights` (the scene's, so that a bake's tree input is not copied
// again: 4 M samples are 320 MiB); dropped when no triangle emits.
Result<AreaLightSampling> sample_area_lights(const SceneGeometry& geometry, uint32_t budget, uint64_t seed,
                                             IndexRange samples = {}, const BakeStop* stop = nullptr,
                                             std::vector<SceneLight> before = {});

// Per channel, pi x L x A: what a triangle of emitted radiance L emits.
glm::dvec3 emitted_power(const SceneGeometry& geometry, const SurfaceTriangle& triangle);

}  // namespace lc::bake

#pragma once
// The bake's indirect stage: picks the solver the request names, runs it on
// the scene's geometry, and says in one census line what it simulated or why
// it skipped. Its lights join the tree as lights marked indirect.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "lightcuts/result.h"
#include "lightcuts/scene_geometry.h"
#include "lightcuts/scene_light.h"
#include "lightmass_server/indirect/indirect_light.h"
#include "lightmass_server/indirect/radiosity_solver.h"
#include "lightmass_server/indirect/vpl_tracer.h"
#include "lightmass_server/raycast/ray_caster.h"
#include "lightmass_server/builders/tree_builder.h"

namespace lc::bake {

struct IndirectOptions {
    IndirectMethod method = IndirectMethod::kOff;
    VplOptions vpl;
    RadiosityOptions radiosity;
};

// The solvers' settings from a bake request; `seed` seeds the photon paths.
IndirectOptions indirect_options(const IndirectRequest& request, uint64_t seed);

struct IndirectStageResult {
    std::vector<IndirectLight> lights;
    // "simulated (...)" or "skipped: ...", after "indirect: " in logs and stats.
    std::string census;
    // Things a person should know (a radiosity budget that ran out).
    std::vector<std::string> warnings;
    // Set for radiosity, for --radiosity-out.
    std::vector<Patch> patches;
    std::vector<glm::vec3> patch_radiosity;
};

// Oriented (cosine) tree lights, in order, with GUIDs from their index.
// `first_index`: the first light's index among every part's (a rank's share of an MPI bake).
std::vector<SceneLight> as_tree_lights(std::span<const IndirectLight> lights, uint64_t first_index = 0);

// `caster` may be null when the geometry is empty.
Result<IndirectStageResult> run_indirect_stage(const SceneGeometry& geometry, const RayCaster* caster,
                                               std::span<const SceneLight> lights, const IndirectOptions& options,
                                               const ProgressFn& progress);

}  // namespace lc::bake

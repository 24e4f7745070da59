#pragma once
// Progressive-refinement radiosity (Cohen, Chen, Wallace and Greenberg 1988):
// the patch with the most unshot power shoots it to every patch it sees,
// until the unshot power falls below a tolerance of the total. Form factors
// are point-to-polygon (exact when unoccluded) times the fraction of
// visibility rays Embree lets through; each receiver is evaluated at its
// centre, so a step is one pass over the patches, in parallel, deterministic;
// the receivers may be split over processes (radiosity_parts.h).
#include <glm/vec3.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "lightcuts/result.h"
#include "lightcuts/scene_geometry.h"
#include "lightcuts/scene_light.h"
#include "lightmass_server/control/bake_stop.h"
#include "lightmass_server/indirect/indirect_light.h"
#include "lightmass_server/indirect/patch_mesh.h"
#include "lightmass_server/indirect/radiosity_parts.h"
#include "lightmass_server/raycast/ray_caster.h"
#include "lightmass_server/builders/tree_builder.h"

namespace lc::bake {

struct RadiosityOptions {
    float patch_size = 0.25f;   // target edge length, scene units
    double tolerance = 0.01;    // stop when unshot power <= tolerance x total power
    uint64_t max_steps = 100000;
    size_t max_patches = size_t(1) << 21;
    // Visibility rays per shooter-receiver pair: 1 (the shooter's centre) or 4.
    uint32_t visibility_samples = 4;
    const BakeStop* stop = nullptr;  // polled every chunk of patches; null: runs to the end
    // Null: one process solves every patch. Else this process is one part
    // (radiosity_parts.h): it shoots into its receivers only, and its result's
    // lights, radiosity and emission are its receivers' alone (the lights of
    // the parts, concatenated in part order, are the one-process lights).
    const RadiosityParts* parts = nullptr;
};

struct ConvergencePoint {
    uint64_t step = 0;
    double seconds = 0.0;
    double shot_fraction = 0.0;  // of the total power, shot so far
};

struct RadiosityResult {
    PatchMesh mesh;
    std::vector<glm::vec3> radiosity;  // B per patch: all power leaving, W/m^2, linear RGB
    std::vector<glm::vec3> emission;   // E per patch: its own emission, W/m^2
    // One cosine emitter per patch with reflected light: power (B - E) x area.
    std::vector<IndirectLight> lights;
    uint64_t steps = 0;
    double unshot_fraction = 0.0;  // unshot over total power when it stopped
    // The ambient radiosity that stands for the unshot power (W/m^2); each
    // patch's radiosity includes its albedo times it.
    glm::dvec3 ambient{0.0};
    bool converged = true;
    // Empty when it converged; else says why it stopped and what to change.
    std::string message;
    std::vector<ConvergencePoint> convergence;
};

// Punctual lights shoot first (their direct light, with a shadow ray per
// patch), then emissive and lit patches shoot progressively. Progress: stage
// "radiosity", percent of the total power shot; cancelling gives an error of
// kind ErrorKind::kCancelled. A step budget that ends first is not an error:
// the result says so in `converged` and `message`.
Result<RadiosityResult> solve_radiosity(const SceneGeometry& geometry, const RayCaster& caster,
                                        std::span<const SceneLight> lights, const RadiosityOptions& options,
                                        const ProgressFn& progress);

}  // namespace lc::bake

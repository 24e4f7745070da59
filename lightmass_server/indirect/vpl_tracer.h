#pragma once
// Instant radiosity (Keller 1997; the Lightcuts paper, section 3): particles
// leave the scene's lights in proportion to power, are traced through the
// scene's surfaces, and leave an indirect light at every diffuse hit.
#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/result.h"
#include "lightcuts/scene_geometry.h"
#include "lightcuts/scene_light.h"
#include "lightmass_server/control/bake_stop.h"
#include "lightmass_server/builders/index_range.h"
#include "lightmass_server/indirect/indirect_light.h"
#include "lightmass_server/raycast/ray_caster.h"
#include "lightmass_server/builders/tree_builder.h"

namespace lc::bake {

// Each VPL carries the bounce that left it (FLightData.light_source_length,
// docs/PROTOCOL.md); a deeper request is refused, not truncated.
inline constexpr uint32_t kMaxVplBounces = kMaxRecordedBounce;

struct VplOptions {
    uint64_t particle_count = 100000;  // light paths; each leaves up to `bounces` lights
    // Diffuse hits that deposit a light, <= kMaxVplBounces; by default every
    // one a path reaches before Russian roulette ends it.
    uint32_t bounces = kMaxVplBounces;
    uint64_t seed = 0;
    // The paths this process traces (an MPI rank's share); the default: all.
    IndexRange particles;
    // The tracer stops with a "too large" error once the paths have left this many lights.
    uint64_t max_lights = uint64_t{1} << 22;
    const BakeStop* stop = nullptr;  // polled every bounce; null: runs to the end
};

struct VplResult {
    // In particle order, then bounce order: the same bytes at any thread count.
    std::vector<IndirectLight> lights;
    uint64_t particles = 0;
    glm::dvec3 emitted_power{0.0};  // what the particles left the lights with
};

// Each particle draws from its own counter-based stream (seed, particle index).
// Surfaces reflect from their front side (the side their normals face), like
// radiosity patches; a particle that reaches a back face is absorbed.
// Progress: stage "indirect", percent of particles traced; cancelling (the
// callback returns false, or `stop` asks) gives an error of kind
// ErrorKind::kCancelled; `stop`'s deadline gives its own error.
Result<VplResult> trace_vpls(const SceneGeometry& geometry, const RayCaster& caster,
                             std::span<const SceneLight> lights, const VplOptions& options,
                             const ProgressFn& progress);

}  // namespace lc::bake

#pragma once
// The lights a radiosity patch leaves for the renderer. A patch's light sits at
// its centre, which is far from a crease: a floor point at the foot of a wall
// sees the wall patch's centre straight above it, where a cosine emitter sends
// nothing, while the patch itself covers the crease. Patches near a contact
// (another surface within about a patch of their centre) are therefore left as
// 4^levels lights, one per midpoint sub-triangle, of the patch's radiosity.
#include <glm/vec3.hpp>

#include <vector>

#include "lightmass_server/indirect/indirect_light.h"
#include "lightmass_server/indirect/patch_mesh.h"
#include "lightmass_server/raycast/ray_caster.h"

namespace lc::bake {

// Midpoint subdivision levels of a patch near a contact (measured on the
// Cornell box against Cycles: docs/bench/truth2.md).
inline constexpr int kContactLightLevels = 2;

// Whether another surface lies within about a patch of `p`'s centre, across
// its plane: segments just above the patch, towards and past its corners and
// edge midpoints, reach something. `epsilon` is the scene's ray offset.
bool near_contact(const Patch& p, const RayCaster& caster, float epsilon);

// Appends the lights of patch `p`, whose reflected radiosity (B - E, W/m^2) is
// `reflected`, lifted `epsilon` off its front: one at its centre, or 4^levels
// over its midpoint sub-triangles, each with its share of the power and the
// disk radius of its area.
void append_patch_lights(const Patch& p, glm::dvec3 reflected, float epsilon, int levels,
                         std::vector<IndirectLight>& out);

}  // namespace lc::bake

#pragma once
// The scene's surfaces for the server (lightcuts/scene_geometry.h), made from
// the client's Scene: every drawn triangle in world space with one material.
// Emissive and base-colour textures are reduced per triangle (the texture's
// mean over the triangle), so one record says what the triangle emits and
// reflects and the server needs no textures; docs/PROTOCOL.md says why.
// Alpha masks travel as keep bits, so the server's rays pass cut-outs, and a
// surface that casts no shadow (BLEND, transmission) as a mask keeping nothing.
#include <memory>

#include "lightcuts/scene.h"
#include "lightcuts/scene_geometry.h"
#include "protocol/messages.h"

namespace lc::client {

// Barycentric points per triangle at which a texture is read for its mean.
inline constexpr int kTextureReductionSamples = 36;

SceneGeometry extract_surface_geometry(const Scene& scene);

// Whether some drawn triangle emits power (emission > 0 over a non-zero
// area): what makes the bake need the geometry channel today.
bool emits_power(const SceneGeometry& geometry);
// Drawn triangles that emit power.
size_t emissive_triangle_count(const SceneGeometry& geometry);

// The geometry a bake of `scene` must send, or null when no effect needs it
// (no drawn triangle emits power and no indirect light is asked for), so such
// a bake sends what it always did.
std::shared_ptr<const SceneGeometry> geometry_the_bake_needs(const Scene& scene,
                                                             IndirectMethod indirect = IndirectMethod::kOff);

}  // namespace lc::client

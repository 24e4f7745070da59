// Specialization-constant ids, written once for the C++ that sets them
// (vk::Specialization) and the shaders that declare them
// (layout(constant_id = kSpec...)). Values are chosen by scene_effects and
// the render settings; float constants travel as their bits.
#ifndef LC_DEVICE_SPEC_CONSTANTS_H
#define LC_DEVICE_SPEC_CONSTANTS_H

#include "lightcuts/device/glsl_compat.h"

LC_DEVICE_BEGIN

// Every compute pass: the workgroup size (local_size_x_id / local_size_y_id).
LC_CONST uint kSpecWorkgroupX = 0u;
LC_CONST uint kSpecWorkgroupY = 1u;
// The lighting passes' effects (shaders/effects.glsl): what the scene holds.
LC_CONST uint kSpecPointLights = 2u;
LC_CONST uint kSpecSpotLights = 3u;
LC_CONST uint kSpecDirectionalLights = 4u;
LC_CONST uint kSpecRangeWindow = 5u;
LC_CONST uint kSpecClassicLights = 6u;
LC_CONST uint kSpecEmissive = 7u;
LC_CONST uint kSpecOrientedLights = 21u;
LC_CONST uint kSpecShadows = 19u;   // shadow_rays.glsl
LC_CONST uint kSpecAlphaMasks = 27u;  // shadow_rays.glsl: some occluder is alpha-masked
LC_CONST uint kSpecSpecular = 20u;  // material_model.glsl
// cut_view.comp: what it shows.
LC_CONST uint kSpecCutView = 9u;
LC_CONST uint kCutViewCuts = 0u;     // each distinct cut a colour
LC_CONST uint kCutViewCutSize = 1u;  // heatmap of cut sizes
// gbuffer.frag: sample the material's textures.
LC_CONST uint kSpecTextures = 10u;
// The bound criterion (lightcuts_bound_walk.comp, lightcuts_bound_heap.comp);
// the error ratio also sets every lighting pass's indirect clamp.
LC_CONST uint kSpecErrorRatio = 11u;  // float bits
LC_CONST uint kSpecMaxCut = 12u;      // the max-cut setting
// The heap's entries in private memory: max-cut, or less where the driver
// refuses that much (BoundHeapPass).
LC_CONST uint kSpecHeapCapacity = 29u;
LC_CONST uint kSpecWalkMaxCut = 14u;
LC_CONST uint kSpecWalkMaxPasses = 15u;
LC_CONST uint kSpecWalkShrink = 16u;  // float bits
LC_CONST uint kSpecWalkMargin = 17u;  // float bits
LC_CONST uint kSpecWalkBisections = 18u;
// Indirect lights in the tree (shaders/indirect_clamp.glsl): clamped, or left out.
LC_CONST uint kSpecIndirectClamp = 22u;
LC_CONST uint kSpecIndirectOff = 23u;
// The walk search refines one cut for every lane of a subgroup (RenderSettings::share_cuts).
LC_CONST uint kSpecWalkShareCuts = 24u;
// Which leaf evaluates a cluster of the bound criterion: the tree's
// representative or one drawn per pixel (kRepresentatives*,
// pixel_representative.glsl.h; RenderSettings::representatives), and the
// draws' seed.
LC_CONST uint kSpecRepresentatives = 25u;
LC_CONST uint kSpecRepresentativeSeed = 26u;
// The real-time mode (realtime_lighting.comp): nodes in a block's cut, at most
// kMaxStochasticCut (limits.h).
LC_CONST uint kSpecStochasticCut = 28u;
// Its shadow rays per pixel, picked among the cut's drawn lights (0: one per
// cut node; shaders/shadow_ray_budget.glsl).
LC_CONST uint kSpecStochasticRays = 30u;
// Reconstruction cuts (lightcuts_reconstruction_*.comp): the side of the
// blocks whose corners are samples, and the records one sample keeps at most.
LC_CONST uint kSpecReconstructionBlock = 31u;
LC_CONST uint kSpecReconstructionCap = 32u;

LC_DEVICE_END

#endif

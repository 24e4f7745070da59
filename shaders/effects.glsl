// Specialization constants shared by the lighting passes; scene_effects
// decides their values, lightcuts/device/spec_constants.h numbers them.
#ifndef LC_EFFECTS_GLSL
#define LC_EFFECTS_GLSL

#include "lightcuts/device/spec_constants.h"

layout(constant_id = kSpecPointLights) const bool kPointLights = true;
layout(constant_id = kSpecSpotLights) const bool kSpotLights = true;
layout(constant_id = kSpecDirectionalLights) const bool kDirectionalLights = true;
layout(constant_id = kSpecOrientedLights) const bool kOrientedLights = true;
layout(constant_id = kSpecRangeWindow) const bool kRangeWindow = true;
layout(constant_id = kSpecClassicLights) const bool kClassicLights = true;
layout(constant_id = kSpecEmissive) const bool kEmissive = true;

#endif

// Specialization constants shared by the lighting passes. The ids match
// SpecId in editor_client/render/renderer.cpp; scene_effects decides values.
#ifndef LC_EFFECTS_GLSL
#define LC_EFFECTS_GLSL

// ids 0 and 1 are the workgroup size (local_size_x_id / local_size_y_id).
layout(constant_id = 2) const bool kPointLights = true;
layout(constant_id = 3) const bool kSpotLights = true;
layout(constant_id = 4) const bool kDirectionalLights = true;
layout(constant_id = 5) const bool kRangeWindow = true;
layout(constant_id = 6) const bool kClassicLights = true;
layout(constant_id = 7) const bool kEmissive = true;

#endif

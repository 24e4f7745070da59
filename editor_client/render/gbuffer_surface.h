#pragma once
// A G-buffer read-back's pixel as the CPU evaluator's surface point: what the
// lighting pass saw there (material_model.h's glTF metallic-roughness split).
#include <cstddef>

#include "editor_client/render/renderer.h"
#include "lightcuts/cuts/cpu_evaluator.h"

namespace lc::client {

// Pixel i of `g` (without occluders: the caller adds them when shadows are on).
SurfacePoint gbuffer_surface_point(const GBufferReadback& g, size_t i);

}  // namespace lc::client

#include "editor_client/render/passes/lightcuts_pass.h"

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"
#include "lightcuts_bound_heap_comp.spv.h"
#include "lightcuts_bound_walk_comp.spv.h"
#include "lightcuts_radius_comp.spv.h"

namespace lc::client {

// One module per cut search (shaders/lightcuts_*.comp).
std::span<const uint32_t> lightcuts_module(LightcutsAlgorithm algorithm) {
    switch (algorithm) {
        case LightcutsAlgorithm::kRadiusWalk: return spirv_words(lightcuts_radius_comp_spv);
        case LightcutsAlgorithm::kBoundWalk: return spirv_words(lightcuts_bound_walk_comp_spv);
        case LightcutsAlgorithm::kBoundHeap: return spirv_words(lightcuts_bound_heap_comp_spv);
    }
    return spirv_words(lightcuts_bound_walk_comp_spv);
}

std::span<const uint32_t> LightcutsPass::module(const Frame&) const {
    return lightcuts_module(algorithm_);
}

void LightcutsPass::specialize(vk::Specialization& spec, const Frame& frame) const {
    LightingPass::specialize(spec, frame);
    // shaders/pixel_representative.glsl (the radius walk is refused per-pixel
    // representatives by validate()).
    spec.set_uint(kSpecRepresentatives, static_cast<uint32_t>(frame.settings->representatives))
        .set_uint(kSpecRepresentativeSeed, frame.settings->representative_seed);
}

void LightcutsPass::dispatch_all(VkCommandBuffer cmd, const Frame& frame) const {
    dispatch(cmd, frame, frame.constants);
}

}  // namespace lc::client

#include "editor_client/render/passes/lightcuts_pass.h"

#include "editor_client/render/frame_interface.h"
#include "lightcuts_comp.spv.h"

namespace lc::client {

std::span<const uint32_t> lightcuts_module(LightcutsAlgorithm) {
    return spirv_words(lightcuts_comp_spv);
}

std::span<const uint32_t> LightcutsPass::module(const Frame&) const {
    return lightcuts_module(algorithm_);
}

void LightcutsPass::specialize(vk::Specialization& spec, const Frame& frame) const {
    LightingPass::specialize(spec, frame);
    const CutCriterion criterion = algorithm_ == LightcutsAlgorithm::kRadiusWalk
                                       ? CutCriterion::kRadius
                                       : CutCriterion::kBound;
    spec.set_uint(kSpecCriterion, static_cast<uint32_t>(criterion));
}

void LightcutsPass::dispatch_all(VkCommandBuffer cmd, const Frame& frame) const {
    dispatch(cmd, frame, frame.constants);
}

}  // namespace lc::client

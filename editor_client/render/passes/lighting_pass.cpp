#include "editor_client/render/passes/lighting_pass.h"

#include <bit>

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"
#include "editor_client/vk/barriers.h"

namespace lc::client {

void LightingPass::specialize(vk::Specialization& spec, const Frame& frame) const {
    specialize_lighting(spec, frame);
}

void specialize_lighting(vk::Specialization& spec, const Frame& frame) {
    const SceneEffects& effects = *frame.effects;
    spec.set_bool(kSpecPointLights, effects.point_lights)
        .set_bool(kSpecSpotLights, effects.spot_lights)
        .set_bool(kSpecDirectionalLights, effects.directional_lights)
        .set_bool(kSpecOrientedLights, effects.oriented_lights)
        .set_bool(kSpecRangeWindow, effects.range_window)
        .set_bool(kSpecClassicLights, effects.classic_lights)
        .set_bool(kSpecEmissive, effects.emissive)
        .set_bool(kSpecShadows, frame.shadows)
        .set_bool(kSpecAlphaMasks, frame.alpha_masks)
        .set_bool(kSpecSpecular, effects.specular)
        .set_bool(kSpecIndirectClamp, effects.indirect_clamp)
        .set_bool(kSpecIndirectOff, effects.indirect_off);
    // The clamp's ratio is half the error ratio (the bound passes set it anyway);
    // without indirect lights the constant stays out of the pipeline's key.
    if (effects.indirect_clamp)
        spec.set_uint(kSpecErrorRatio, std::bit_cast<uint32_t>(frame.settings->error_ratio));
}

void begin_lighting_images(VkCommandBuffer cmd, const Frame& frame) {
    const VkImageLayout old_layout =
        frame.continues_image ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED;
    for (const vk::Image* image : {&frame.targets->hdr, &frame.targets->cut}) {
        vk::transition_image(cmd, {image->handle(), old_layout, VK_IMAGE_LAYOUT_GENERAL,
                                   kComputeStage, kStorageReadWrite, kComputeStage, kStorageWrite});
    }
}

void LightingPass::record(VkCommandBuffer cmd, const Frame& frame) const {
    begin_lighting_images(cmd, frame);
    bind(cmd, frame);
    dispatch_all(cmd, frame);
}

}  // namespace lc::client

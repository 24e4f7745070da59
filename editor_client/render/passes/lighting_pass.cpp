#include "editor_client/render/passes/lighting_pass.h"

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"
#include "editor_client/vk/barriers.h"

namespace lc::client {

void LightingPass::specialize(vk::Specialization& spec, const Frame& frame) const {
    const SceneEffects& effects = *frame.effects;
    spec.set_bool(kSpecPointLights, effects.point_lights)
        .set_bool(kSpecSpotLights, effects.spot_lights)
        .set_bool(kSpecDirectionalLights, effects.directional_lights)
        .set_bool(kSpecOrientedLights, effects.oriented_lights)
        .set_bool(kSpecRangeWindow, effects.range_window)
        .set_bool(kSpecClassicLights, effects.classic_lights)
        .set_bool(kSpecEmissive, effects.emissive)
        .set_bool(kSpecShadows, frame.shadows)
        .set_bool(kSpecSpecular, effects.specular);
}

void LightingPass::record(VkCommandBuffer cmd, const Frame& frame) const {
    // Every pixel of hdr and cut is written, so old contents are dropped.
    for (const vk::Image* image : {&frame.targets->hdr, &frame.targets->cut}) {
        vk::transition_image(cmd, {image->handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                                   kComputeStage, kStorageReadWrite, kComputeStage, kStorageWrite});
    }
    bind(cmd, frame);
    dispatch_all(cmd, frame);
}

}  // namespace lc::client

#pragma once
// Reference lighting: every tree leaf (or scene light) and every classic
// light at every pixel, exact; split over dispatches that each stay within
// the device's loop limit.
#include "editor_client/render/passes/lighting_pass.h"

namespace lc::client {

class ReferencePass final : public LightingPass {
protected:
    std::span<const uint32_t> module(const Frame& frame) const override;
    void dispatch_all(VkCommandBuffer cmd, const Frame& frame) const override;
};

}  // namespace lc::client

#pragma once
// Lightcuts lighting: a cut of the light tree per pixel, each cut node
// evaluated as a cluster. One subclass per algorithm that finds the cut.
#include "editor_client/render/passes/lighting_pass.h"

namespace lc::client {

enum class LightcutsAlgorithm : uint8_t {
    kRadiusWalk,  // refine nodes whose bounds the pixel is inside (radius criterion)
    kBoundWalk,   // the bound criterion by threshold passes (bound_walk.h)
    kBoundHeap,   // the bound criterion by the paper's heap
};

// The SPIR-V module that runs an algorithm (the one place that chooses it).
std::span<const uint32_t> lightcuts_module(LightcutsAlgorithm algorithm);

class LightcutsPass : public LightingPass {
protected:
    explicit LightcutsPass(LightcutsAlgorithm algorithm) : algorithm_(algorithm) {}

    std::span<const uint32_t> module(const Frame& frame) const final;
    // Every lighting constant and the cut criterion.
    void specialize(vk::Specialization& spec, const Frame& frame) const override;
    // One dispatch over the image.
    void dispatch_all(VkCommandBuffer cmd, const Frame& frame) const override;

private:
    LightcutsAlgorithm algorithm_;
};

}  // namespace lc::client

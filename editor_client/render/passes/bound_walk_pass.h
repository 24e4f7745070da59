#pragma once
// Lightcuts with the bound criterion by threshold passes (bound_walk.h): each
// pass a pre-order walk shared by the subgroup, the search kept per pixel in
// the walk-state buffer between dispatches.
#include "editor_client/render/passes/lightcuts_pass.h"

namespace lc::client {

class BoundWalkPass final : public LightcutsPass {
public:
    BoundWalkPass() : LightcutsPass(LightcutsAlgorithm::kBoundWalk) {}

protected:
    void specialize(vk::Specialization& spec, const Frame& frame) const override;
    void dispatch_all(VkCommandBuffer cmd, const Frame& frame) const override;
};

}  // namespace lc::client

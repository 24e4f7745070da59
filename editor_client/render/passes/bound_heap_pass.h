#pragma once
// Lightcuts with the bound criterion, the paper's search: a max-heap of cut
// nodes by error bound, refined until every bound is within the error ratio
// or the cut holds max-cut nodes. The heap lives in private memory, sized by
// max-cut at pipeline creation.
#include "editor_client/render/passes/lightcuts_pass.h"

namespace lc::client {

class BoundHeapPass final : public LightcutsPass {
public:
    BoundHeapPass() : LightcutsPass(LightcutsAlgorithm::kBoundHeap) {}

protected:
    void specialize(vk::Specialization& spec, const Frame& frame) const override;
};

}  // namespace lc::client

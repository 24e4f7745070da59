#include "editor_client/render/passes/bound_heap_pass.h"

#include <algorithm>
#include <bit>

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"

namespace lc::client {

void BoundHeapPass::specialize(vk::Specialization& spec, const Frame& frame) const {
    LightcutsPass::specialize(spec, frame);
    // Room for one refinement (two children) even at max-cut 1.
    spec.set_uint(kSpecErrorRatio, std::bit_cast<uint32_t>(frame.settings->error_ratio))
        .set_uint(kSpecMaxCut, std::max(frame.settings->max_cut, 2u));
}

}  // namespace lc::client

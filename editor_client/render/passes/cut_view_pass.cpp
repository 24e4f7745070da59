#include "editor_client/render/passes/cut_view_pass.h"

#include "cut_view_comp.spv.h"
#include "lightcuts/device/bindings.h"
#include "lightcuts/device/spec_constants.h"

namespace lc::client {

std::span<const uint32_t> CutViewPass::module(const Frame&) const {
    return spirv_words(cut_view_comp_spv);
}

void CutViewPass::specialize(vk::Specialization& spec, const Frame& frame) const {
    spec.set_uint(kSpecCutView, frame.settings->mode == RenderMode::kCuts ? kCutViewCuts : kCutViewCutSize);
}

}  // namespace lc::client

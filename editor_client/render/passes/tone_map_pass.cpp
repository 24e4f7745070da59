#include "editor_client/render/passes/tone_map_pass.h"

#include "tone_map_comp.spv.h"

namespace lc::client {

std::span<const uint32_t> ToneMapPass::module(const Frame&) const {
    return spirv_words(tone_map_comp_spv);
}

}  // namespace lc::client

#pragma once
// The cut views: each distinct cut a stable colour (cuts mode), or a heatmap
// of the cut size with a colour scale bar (cutsize mode).
#include "editor_client/render/passes/output_pass.h"

namespace lc::client {

class CutViewPass final : public OutputPass {
protected:
    std::span<const uint32_t> module(const Frame& frame) const override;
    void specialize(vk::Specialization& spec, const Frame& frame) const override;
};

}  // namespace lc::client

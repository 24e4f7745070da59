#pragma once
// Tone mapping: exposure, the tone curve and sRGB encoding of the HDR image.
#include "editor_client/render/passes/output_pass.h"

namespace lc::client {

class ToneMapPass final : public OutputPass {
protected:
    std::span<const uint32_t> module(const Frame& frame) const override;
    void specialize(vk::Specialization&, const Frame&) const override {}
};

}  // namespace lc::client

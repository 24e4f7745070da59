#pragma once
// The output pass: the lighting pass's images turned into the 8-bit display
// image (tone mapping, or a visualisation of the cuts).
#include "editor_client/render/passes/compute_pass.h"

namespace lc::client {

class OutputPass : public ComputePass {
public:
    void record(VkCommandBuffer cmd, const Frame& frame) const final;

protected:
    const char* role() const final { return "output"; }
};

}  // namespace lc::client

#pragma once
// The lighting pass: radiance per pixel into the HDR image and the cut (size,
// hash) into the cut image, from the G-buffer and the lights. One subclass
// per algorithm (reference, radius walk, bound walk, bound heap).
#include "editor_client/render/passes/compute_pass.h"

namespace lc::client {

// The effects every lighting shader is specialised for (the scene's light
// types, shadows, the indirect clamp).
void specialize_lighting(vk::Specialization& spec, const Frame& frame);
// The HDR and cut images ready for a lighting pass to write: a new image
// drops the old contents, a continued one keeps the regions already lit.
void begin_lighting_images(VkCommandBuffer cmd, const Frame& frame);

class LightingPass : public ComputePass {
public:
    void record(VkCommandBuffer cmd, const Frame& frame) const final;

protected:
    const char* role() const final { return "lighting"; }
    // The effects every lighting shader is specialised for; subclasses add their own.
    void specialize(vk::Specialization& spec, const Frame& frame) const override;
    // The pass's dispatches, with the frame set and pipeline bound.
    virtual void dispatch_all(VkCommandBuffer cmd, const Frame& frame) const = 0;
};

}  // namespace lc::client

#pragma once
// Reference lighting: every tree leaf (or scene light) and every classic
// light at every pixel, exact; split over dispatches that each stay within
// the device's loop limit, and over submissions that each stay within a
// fence wait (reference_submissions).
#include <vector>

#include "editor_client/render/passes/lighting_pass.h"

namespace lc::client {

class ReferencePass final : public LightingPass {
protected:
    std::span<const uint32_t> module(const Frame& frame) const override;
    // Records the dispatches in frame.reference_dispatches.
    void dispatch_all(VkCommandBuffer cmd, const Frame& frame) const override;
};

// The reference's dispatches over `frame` (its leaves in chunks, then the
// parts' sum on small images), and the light evaluations the largest one makes.
struct ReferenceWork {
    uint32_t dispatches = 1;
    uint64_t evaluations_per_dispatch = 0;
};
ReferenceWork reference_work(const Frame& frame);

// Runs of consecutive dispatches, in order, each making at most
// `evaluations_per_submission` light evaluations (at least one dispatch).
std::vector<DispatchRange> reference_submissions(const Frame& frame,
                                                 uint64_t evaluations_per_submission);

}  // namespace lc::client

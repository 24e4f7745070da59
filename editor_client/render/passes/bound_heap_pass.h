#pragma once
// Lightcuts with the bound criterion, the paper's search: a max-heap of cut
// nodes by error bound, refined until every bound is within the error ratio
// or the cut holds max-cut nodes. The heap lives in private memory, sized at
// pipeline creation: max-cut entries (20 bytes each), or fewer where the
// driver refuses that much private memory (NVIDIA's refused 1,000 entries and
// took 256 on an H200). Pixels that fill the smaller heap count as max-cut
// hits, and the stats name the capacity used.
#include <cstdint>
#include <vector>

#include "editor_client/render/passes/lightcuts_pass.h"

namespace lc::client {

// The capacities tried for a max-cut, largest first: max-cut itself, then
// three quarters of the last, down to kMinHeapCapacity.
inline constexpr uint32_t kMinHeapCapacity = 16;
std::vector<uint32_t> heap_capacities(uint32_t max_cut);

class BoundHeapPass final : public LightcutsPass {
public:
    BoundHeapPass() : LightcutsPass(LightcutsAlgorithm::kBoundHeap) {}

    // The heap's entries in the last pipeline prepared (0 before any).
    uint32_t capacity() const { return capacity_; }

protected:
    void specialize(vk::Specialization& spec, const Frame& frame) const override;
    Result<VkPipeline> create_pipeline(PipelineCache& pipelines, const Frame& frame) override;

private:
    uint32_t capacity_ = 0;
    // The smallest capacity this device refused: never asked again.
    uint32_t smallest_refused_ = UINT32_MAX;
};

}  // namespace lc::client

#pragma once
// Streams a finished tree as the Lightcuts result channel: OpenChannel, the
// count-prefixed records in bounded WriteChannel chunks, CloseChannel, then
// BakeDone. Frames are made one at a time, so a 10^6-node tree never exists
// twice in memory. Each chunk's records are encoded straight into its frame.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "lightcuts/light_tree.h"
#include "protocol/encoded_frame.h"
#include "protocol/messages.h"

namespace lc::bake {

class ResultStream {
public:
    ResultStream(std::shared_ptr<const LightTree> tree, uint32_t channel_id, BakeDoneMsg done,
                 size_t chunk_bytes);

    // The next frame to send, or nothing once BakeDone has been produced.
    std::optional<EncodedFrame> next_frame();

private:
    enum class Stage { kOpen, kData, kClose, kDone, kFinished };

    std::shared_ptr<const LightTree> tree_;
    uint32_t channel_id_;
    BakeDoneMsg done_;
    size_t records_per_chunk_;
    Stage stage_ = Stage::kOpen;
    size_t next_node_ = 0;
    uint64_t offset_ = 0;
};

}  // namespace lc::bake

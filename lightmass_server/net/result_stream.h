#pragma once
// Streams a finished tree as the Lightcuts result channel: OpenChannel, the
// count-prefixed records in bounded WriteChannel chunks, CloseChannel, then
// BakeDone. Frames are made one at a time, so a 10^6-node tree never exists
// twice in memory. Each chunk's records are encoded straight into its frame,
// or copied from a file that holds the channel's bytes.
#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "lightcuts/tree/light_tree.h"
#include "protocol/encoded_frame.h"
#include "protocol/messages.h"

namespace lc::bake {

class ResultChannelFile;

class ResultStream {
public:
    ResultStream(std::shared_ptr<const LightTree> tree, uint32_t channel_id, BakeDoneMsg done,
                 size_t chunk_bytes);
    // The same frames, byte for byte, from a tree kept on disk as the channel's
    // bytes (a bake over MPI ranks): each chunk is read from the file as it is
    // sent. A read that fails ends the stream with an Error for the bake.
    ResultStream(std::shared_ptr<const ResultChannelFile> file, uint32_t channel_id, BakeDoneMsg done,
                 size_t chunk_bytes);

    // The next frame to send, or nothing once BakeDone has been produced.
    std::optional<EncodedFrame> next_frame();

private:
    enum class Stage { kOpen, kData, kClose, kDone, kFinished };

    std::optional<EncodedFrame> next_data_frame();

    std::shared_ptr<const LightTree> tree_;  // one of the two
    std::shared_ptr<const ResultChannelFile> file_;
    size_t node_count_ = 0;
    uint32_t channel_id_;
    BakeDoneMsg done_;
    size_t records_per_chunk_;
    Stage stage_ = Stage::kOpen;
    size_t next_node_ = 0;
    uint64_t offset_ = 0;
};

}  // namespace lc::bake

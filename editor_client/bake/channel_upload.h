#pragma once
// The client's channels on their way to the server, one message at a time:
// each channel opened, written in chunks of at most `chunk_bytes`, closed,
// then the next. The session sends BakeRequest once this is done.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "protocol/messages.h"

namespace lc::client {

struct UploadChannel {
    uint32_t id = 0;
    std::string name;
    std::vector<uint8_t> bytes;
};

class ChannelUpload {
public:
    ChannelUpload(std::vector<UploadChannel> channels, size_t chunk_bytes)
        : channels_(std::move(channels)), chunk_bytes_(chunk_bytes) {}

    // The next OpenChannel, WriteChannel or CloseChannel; nothing once every channel is closed.
    std::optional<Message> next_message();
    bool done() const { return index_ == channels_.size(); }
    // The channels' bytes, moved out (for --record) once done.
    std::vector<UploadChannel> take_channels() { return std::move(channels_); }

private:
    enum class Step { kOpen, kData, kClose };

    std::vector<UploadChannel> channels_;
    size_t chunk_bytes_ = 0;
    Step step_ = Step::kOpen;
    size_t index_ = 0;        // the channel being sent
    uint64_t offset_ = 0;     // its bytes already written
};

}  // namespace lc::client

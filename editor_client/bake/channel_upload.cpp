#include "editor_client/bake/channel_upload.h"

#include <algorithm>

namespace lc::client {

std::optional<Message> ChannelUpload::next_message() {
    if (done()) return std::nullopt;
    const UploadChannel& channel = channels_[index_];
    switch (step_) {
        case Step::kOpen:
            offset_ = 0;
            step_ = channel.bytes.empty() ? Step::kClose : Step::kData;
            return OpenChannelMsg{channel.id, channel.name, channel.bytes.size()};
        case Step::kData: {
            const size_t n = std::min<uint64_t>(chunk_bytes_, channel.bytes.size() - offset_);
            auto begin = channel.bytes.begin() + static_cast<ptrdiff_t>(offset_);
            WriteChannelMsg write{channel.id, offset_, {begin, begin + static_cast<ptrdiff_t>(n)}};
            offset_ += n;
            if (offset_ == channel.bytes.size()) step_ = Step::kClose;
            return write;
        }
        case Step::kClose:
            ++index_;
            step_ = Step::kOpen;
            return CloseChannelMsg{channel.id};
    }
    return std::nullopt;
}

}  // namespace lc::client

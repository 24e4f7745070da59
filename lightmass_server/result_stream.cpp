#include "lightmass_server/result_stream.h"

#include <algorithm>

#include "protocol/channel_records.h"
#include "protocol/codec.h"

namespace lc::bake {

ResultStream::ResultStream(std::shared_ptr<const LightTree> tree, uint32_t channel_id,
                           BakeDoneMsg done, size_t chunk_bytes)
    : tree_(std::move(tree)),
      channel_id_(channel_id),
      done_(std::move(done)),
      records_per_chunk_(std::max<size_t>(1, chunk_bytes / result_record_bytes())) {}

std::optional<EncodedFrame> ResultStream::next_frame() {
    const size_t node_count = tree_->nodes.size();
    switch (stage_) {
        case Stage::kOpen: {
            stage_ = Stage::kData;
            OpenChannelMsg open;
            open.channel_id = channel_id_;
            open.name = done_.result_channel;
            open.total_bytes = 4 + static_cast<uint64_t>(node_count) * result_record_bytes();
            return encode_frame_in_place(open);
        }
        case Stage::kData: {
            const std::vector<uint8_t> prefix =
                offset_ == 0 ? encode_result_prefix(static_cast<uint32_t>(node_count)) : std::vector<uint8_t>{};
            const size_t first = next_node_;
            const size_t count = std::min(records_per_chunk_, node_count - first);
            const size_t data_bytes = prefix.size() + count * result_record_bytes();
            EncodedFrame frame =
                encode_write_channel_frame(channel_id_, offset_, data_bytes, [&](std::span<uint8_t> data) {
                    std::copy(prefix.begin(), prefix.end(), data.begin());
                    write_result_records(*tree_, first, count, data.subspan(prefix.size()));
                });
            next_node_ += count;
            offset_ += data_bytes;
            if (next_node_ == node_count) stage_ = Stage::kClose;
            return frame;
        }
        case Stage::kClose:
            stage_ = Stage::kDone;
            return encode_frame_in_place(CloseChannelMsg{channel_id_});
        case Stage::kDone:
            stage_ = Stage::kFinished;
            return encode_frame_in_place(done_);
        case Stage::kFinished:
            break;
    }
    return std::nullopt;
}

}  // namespace lc::bake

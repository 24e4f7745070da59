#include "lightmass_server/net/result_stream.h"

#include <algorithm>

#include "protocol/channel_records.h"
#include "lightmass_server/bake/result_channel_file.h"
#include "protocol/codec.h"

namespace lc::bake {

ResultStream::ResultStream(std::shared_ptr<const LightTree> tree, uint32_t channel_id,
                           BakeDoneMsg done, size_t chunk_bytes)
    : tree_(std::move(tree)),
      node_count_(tree_->nodes.size()),
      channel_id_(channel_id),
      done_(std::move(done)),
      records_per_chunk_(std::max<size_t>(1, chunk_bytes / result_record_bytes())) {}

ResultStream::ResultStream(std::shared_ptr<const ResultChannelFile> file, uint32_t channel_id,
                           BakeDoneMsg done, size_t chunk_bytes)
    : file_(std::move(file)),
      node_count_(file_->node_count()),
      channel_id_(channel_id),
      done_(std::move(done)),
      records_per_chunk_(std::max<size_t>(1, chunk_bytes / result_record_bytes())) {}

// The next chunk: the count prefix first, then records_per_chunk_ records.
std::optional<EncodedFrame> ResultStream::next_data_frame() {
    const size_t prefix_bytes = offset_ == 0 ? encode_result_prefix(0).size() : 0;
    const size_t first = next_node_;
    const size_t count = std::min(records_per_chunk_, node_count_ - first);
    const size_t data_bytes = prefix_bytes + count * result_record_bytes();
    std::vector<uint8_t> from_file;
    if (file_) {
        // The file is the channel's bytes: this chunk is the file's bytes at offset_.
        from_file.resize(data_bytes);
        if (Status read = file_->read(offset_, from_file); !read) {
            stage_ = Stage::kFinished;
            return encode_frame_in_place(
                ErrorMsg{done_.bake_id, ErrorCode::kBakeFailed, "the result could not be sent: " + read.error()});
        }
    }
    EncodedFrame frame =
        encode_write_channel_frame(channel_id_, offset_, data_bytes, [&](std::span<uint8_t> data) {
            if (file_) {
                std::copy(from_file.begin(), from_file.end(), data.begin());
                return;
            }
            const std::vector<uint8_t> prefix = offset_ == 0 ? encode_result_prefix(uint32_t(node_count_))
                                                             : std::vector<uint8_t>{};
            std::copy(prefix.begin(), prefix.end(), data.begin());
            write_result_records(*tree_, first, count, data.subspan(prefix.size()));
        });
    next_node_ += count;
    offset_ += data_bytes;
    if (next_node_ == node_count_) stage_ = Stage::kClose;
    return frame;
}

std::optional<EncodedFrame> ResultStream::next_frame() {
    switch (stage_) {
        case Stage::kOpen: {
            stage_ = Stage::kData;
            OpenChannelMsg open;
            open.channel_id = channel_id_;
            open.name = done_.result_channel;
            open.total_bytes = 4 + static_cast<uint64_t>(node_count_) * result_record_bytes();
            return encode_frame_in_place(open);
        }
        case Stage::kData:
            return next_data_frame();
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

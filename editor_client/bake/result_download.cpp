#include "editor_client/bake/result_download.h"

#include "protocol/channel_name.h"

namespace lc::client {

Status ResultDownload::open(const OpenChannelMsg& open) {
    auto name = ChannelName::parse(open.name);
    if (!name || name->version != kLightcutsVersionGuid || name->extension != kLightcutsExtension)
        return make_error("server opened an unexpected channel '" + open.name + "' (expected version " +
                          kLightcutsVersionGuid.to_hex() + ", extension ." + kLightcutsExtension + ")");
    if (channel_id_) return make_error("server opened a second result channel");
    channel_id_ = open.channel_id;
    name_ = open.name;
    expected_bytes_ = open.total_bytes;
    start_ = std::chrono::steady_clock::now();
    return Ok{};
}

Result<std::span<const uint8_t>> ResultDownload::write(const WriteChannelMsg& write) {
    if (!channel_id_ || write.channel_id != *channel_id_)
        return make_error("server wrote to channel " + std::to_string(write.channel_id) + " which is not open");
    const std::span<const uint8_t> data = write.bytes();
    if (write.offset != received_ || received_ + data.size() > expected_bytes_)
        return make_error("result channel out of order or longer than announced");
    if (Status s = reader_.consume(data); !s) return make_error("result channel: " + s.error());
    received_ += data.size();
    if (keep_bytes_) bytes_.insert(bytes_.end(), data.begin(), data.end());
    return data;
}

Status ResultDownload::close(const CloseChannelMsg& close) {
    if (!channel_id_ || close.channel_id != *channel_id_) return make_error("server closed a channel that is not open");
    closed_ = true;
    return Ok{};
}

std::optional<float> ResultDownload::percent() const {
    if (reader_.nodes_expected() <= 0) return std::nullopt;
    return 100.0f * static_cast<float>(reader_.nodes_received()) / static_cast<float>(reader_.nodes_expected());
}

double ResultDownload::ms_since_open() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
}

}  // namespace lc::client

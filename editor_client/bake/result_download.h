#pragma once
// The result channel on its way in: its name checked on open, its chunks in
// order and within the announced size, its records decoded (or only
// validated) as they arrive, its bytes kept where the outcome or a recording
// needs them. Each step answers an error that ends the bake.
#include <chrono>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "lightcuts/result.h"
#include "protocol/channel_records.h"
#include "protocol/messages.h"

namespace lc::client {

class ResultDownload {
public:
    ResultDownload(TreeImport import, bool keep_bytes) : reader_(import), keep_bytes_(keep_bytes) {}

    Status open(const OpenChannelMsg& open);
    // The chunk's bytes, consumed (valid records, in order, within the size).
    Result<std::span<const uint8_t>> write(const WriteChannelMsg& write);
    Status close(const CloseChannelMsg& close);

    bool is_open() const { return channel_id_.has_value(); }
    bool closed() const { return closed_; }
    const std::string& name() const { return name_; }
    // Percent of the announced nodes received; none before the count arrived.
    std::optional<float> percent() const;
    double ms_since_open() const;

    ResultChannelReader& reader() { return reader_; }
    std::vector<uint8_t> take_bytes() { return std::exchange(bytes_, std::vector<uint8_t>()); }

private:
    ResultChannelReader reader_;
    bool keep_bytes_ = false;
    std::optional<uint32_t> channel_id_;
    std::string name_;
    uint64_t expected_bytes_ = 0;
    uint64_t received_ = 0;
    bool closed_ = false;
    std::vector<uint8_t> bytes_;
    std::chrono::steady_clock::time_point start_;
};

}  // namespace lc::client

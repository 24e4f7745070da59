#pragma once
// A client channel on its way into the server: which of the three kinds it
// is (by its name's extension), the most bytes that kind may announce, and
// the push decoder that reads it. The session keeps one per open channel id.
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "lightcuts/result.h"
#include "lightmass_server/net/memory_budget.h"
#include "protocol/channel_records.h"
#include "protocol/environment_records.h"
#include "protocol/geometry_channel.h"

namespace lc::bake {

enum class ChannelKind { kScene, kGeometry, kEnvironment };

// "scene", "geometry", "environment": how errors name the channel.
const char* channel_kind_name(ChannelKind kind);
// The kind a channel's extension names; none: not a channel this server reads.
std::optional<ChannelKind> channel_kind_of_extension(const std::string& extension);

// The most bytes a channel of this kind may announce, and the limit in words.
struct ChannelLimit {
    uint64_t max_bytes = 0;
    std::string words;  // "4194304 lights"
};
ChannelLimit channel_limit(ChannelKind kind);

class IncomingChannel {
public:
    using Reader = std::variant<SceneChannelReader, GeometryChannelReader, EnvironmentChannelReader>;

    IncomingChannel(std::string name, ChannelKind kind, uint64_t total_bytes, BudgetReservation reservation);

    const std::string& name() const { return name_; }
    ChannelKind kind() const { return static_cast<ChannelKind>(reader_.index()); }
    // "geometry channel 'NAME'": the start of every error about it.
    std::string label() const;
    uint64_t total_bytes() const { return total_bytes_; }
    uint64_t received() const { return received_; }
    bool complete() const { return received_ == total_bytes_; }

    // The next bytes, in order; `record` keeps a copy for --record. Fails on
    // bytes past the announced total or ones the reader refuses.
    Status consume(std::span<const uint8_t> data, bool record);

    Reader& reader() { return reader_; }
    std::vector<uint8_t> take_recorded() { return std::move(recorded_); }
    BudgetReservation take_reservation() { return std::move(reservation_); }

private:
    std::string name_;
    uint64_t total_bytes_ = 0;
    uint64_t received_ = 0;
    Reader reader_;
    std::vector<uint8_t> recorded_;  // kept only when recording
    BudgetReservation reservation_;
};

}  // namespace lc::bake

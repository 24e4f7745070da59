#include "lightmass_server/net/incoming_channel.h"

#include <utility>

#include "protocol/bake_limits.h"
#include "protocol/channel_name.h"

namespace lc::bake {

const char* channel_kind_name(ChannelKind kind) {
    switch (kind) {
        case ChannelKind::kScene: return "scene";
        case ChannelKind::kGeometry: return "geometry";
        case ChannelKind::kEnvironment: return "environment";
    }
    return "scene";
}

std::optional<ChannelKind> channel_kind_of_extension(const std::string& extension) {
    if (extension == kSceneExtension) return ChannelKind::kScene;
    if (extension == kGeometryExtension) return ChannelKind::kGeometry;
    if (extension == kEnvironmentChannelExtension) return ChannelKind::kEnvironment;
    return std::nullopt;
}

ChannelLimit channel_limit(ChannelKind kind) {
    switch (kind) {
        case ChannelKind::kEnvironment:
            return {max_environment_channel_bytes(),
                    std::to_string(kMaxEquirectWidth) + " x " + std::to_string(kMaxEquirectHeight) + " texels"};
        case ChannelKind::kGeometry:
            return {max_geometry_channel_bytes(), std::to_string(kMaxGeometryMaterials) + " materials and " +
                                                      std::to_string(kMaxGeometryTriangles) +
                                                      " triangles and their masks"};
        case ChannelKind::kScene: break;
    }
    return {4 + uint64_t{kMaxSceneLights} * scene_record_bytes(), std::to_string(kMaxSceneLights) + " lights"};
}

// The reader of a kind: the variant's alternatives are in ChannelKind's order.
static IncomingChannel::Reader reader_for(ChannelKind kind) {
    switch (kind) {
        case ChannelKind::kGeometry: return GeometryChannelReader{};
        case ChannelKind::kEnvironment: return EnvironmentChannelReader{};
        case ChannelKind::kScene: break;
    }
    return SceneChannelReader{};
}

IncomingChannel::IncomingChannel(std::string name, ChannelKind kind, uint64_t total_bytes,
                                 BudgetReservation reservation)
    : name_(std::move(name)), total_bytes_(total_bytes), reader_(reader_for(kind)),
      reservation_(std::move(reservation)) {}

std::string IncomingChannel::label() const {
    return std::string(channel_kind_name(kind())) + " channel '" + name_ + "'";
}

Status IncomingChannel::consume(std::span<const uint8_t> data, bool record) {
    if (received_ + data.size() > total_bytes_)
        return make_error("more bytes than the " + std::to_string(total_bytes_) + " announced");
    Status consumed = std::visit([&](auto& reader) { return reader.consume(data); }, reader_);
    if (!consumed) return consumed;
    received_ += data.size();
    if (record) recorded_.insert(recorded_.end(), data.begin(), data.end());
    return Ok{};
}

}  // namespace lc::bake

#include "protocol/channel_recorder.h"

#include "protocol/dump.h"

namespace lc {

Status ChannelRecorder::record(const std::string& channel_name, std::span<const uint8_t> payload) const {
    if (!enabled()) return Ok{};
    std::error_code ec;
    std::filesystem::create_directories(dir_, ec);
    if (ec) return make_error("cannot create record folder '" + dir_.string() + "': " + ec.message());
    ChannelDump dump;
    dump.channel_name = channel_name;
    dump.payload.assign(payload.begin(), payload.end());
    return write_dump(dump_path_for(dir_, channel_name), dump);
}

}  // namespace lc

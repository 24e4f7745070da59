#pragma once
// --record DIR: writes every channel a program sends or receives as a dump file
// (protocol/dump.h), so tests can replay real traffic.
#include <filesystem>
#include <span>
#include <string>

#include "lightcuts/result.h"

namespace lc {

class ChannelRecorder {
public:
    explicit ChannelRecorder(std::filesystem::path dir) : dir_(std::move(dir)) {}
    bool enabled() const { return !dir_.empty(); }
    // Writes <dir>/<channel name>.dump; creates the folder when needed.
    Status record(const std::string& channel_name, std::span<const uint8_t> payload) const;

private:
    std::filesystem::path dir_;
};

}  // namespace lc

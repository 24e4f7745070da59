#pragma once
// What lightmass_server is told on its command line.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "protocol/frame_decoder.h"

namespace lc::bake {

struct ServerOptions {
    std::string host = "127.0.0.1";
    uint16_t port = 0;  // 0: the system picks a free port
    unsigned bake_threads = 1;
    std::filesystem::path record_dir;    // empty: no recording
    std::optional<std::string> token;    // required when host is not loopback
    uint32_t max_frame_bytes = kDefaultMaxFrameBytes;
    // A peer that stops mid-frame for this long is dropped.
    std::chrono::milliseconds read_timeout{30000};
    // A peer with no bake running that sends nothing for this long is dropped.
    std::chrono::milliseconds idle_timeout{600000};
};

// True for 127.0.0.0/8, ::1 and "localhost".
bool is_loopback_host(const std::string& host);

}  // namespace lc::bake

#pragma once
// What lightmass_server is told on its command line.
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "lightmass_server/bake/mpi_launch_options.h"
#include "protocol/frame_decoder.h"
#include "lightcuts/result.h"

namespace lc::bake {

struct ServerOptions {
    std::string host = "127.0.0.1";
    uint16_t port = 0;  // 0: the system picks a free port
    unsigned bake_threads = 1;
    std::filesystem::path record_dir;    // empty: no recording
    // Each radiosity bake's solved patches as a PLY here (radiosity_ply.h); empty: none.
    std::filesystem::path radiosity_out;
    std::optional<std::string> token;    // required when host is not loopback
    // PEM files; both set: every connection speaks TLS. Required off loopback.
    std::filesystem::path tls_certificate;
    std::filesystem::path tls_private_key;
    uint32_t max_frame_bytes = kDefaultMaxFrameBytes;
    // A peer that stops mid-frame for this long is dropped.
    std::chrono::milliseconds read_timeout{30000};
    // A peer with no bake running that sends nothing for this long is dropped.
    std::chrono::milliseconds idle_timeout{600000};
    // A frame must arrive whole within this long of its first byte, however
    // steadily it trickles in (16 MiB at 1 MiB/s takes 16 s).
    std::chrono::milliseconds frame_timeout{60000};
    // A peer must finish the TLS handshake and say Hello within this long of connecting.
    std::chrono::milliseconds connect_timeout{10000};
    // Connections beyond this many are answered "server busy" after their Hello.
    uint32_t max_connections = 256;
    // Announced bytes of every connection's scene channels and stored scenes together;
    // a channel that does not fit is refused as "server busy".
    uint64_t memory_budget_bytes = uint64_t{4096} << 20;
    // How a bake that asks for MPI ranks is launched (--mpi-* flags).
    MpiLaunchOptions mpi;
    // A bake still running this long after its request is stopped with an error saying so.
    std::chrono::seconds max_bake_time{600};
    // Big bakes at once; 0: from the cores and the budget (bake_lanes.h).
    unsigned max_concurrent_bakes = 0;
    // Bake threads' nice value (bake_priority.h): the I/O thread answers first. 0: no change.
    int bake_nice = 10;
    // Tests only: called on the bake's lane thread before the bake runs (to hold it there).
    std::function<void()> on_bake_thread_start;
};

// True for 127.0.0.0/8, ::1 and "localhost".
bool is_loopback_host(const std::string& host);

// What is missing for these options to be served: a TLS file without its
// pair, or (off loopback) the token or TLS. Names the flags to pass.
Status check_server_security(const ServerOptions& options);

}  // namespace lc::bake

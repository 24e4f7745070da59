// lightmass_server: the Lightcuts bake server. Listens on loopback unless told
// otherwise (then a token and TLS are required), prints "listening on HOST:PORT" first.
#include <CLI/CLI.hpp>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <malloc.h>
#include <unistd.h>

#include <csignal>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iostream>
#include <string>
#include <variant>

#include "lightcuts/version.h"
#include "protocol/asio.h"
#include "lightmass_server/control/journal_log.h"
#include "lightmass_server/control/stale_temporaries.h"
#include "lightmass_server/mpi/host_roster.h"
#include "lightmass_server/mpi/mpi_flags.h"
#include "lightmass_server/net/auth_token.h"
#include "lightmass_server/net/server.h"
#include "protocol/endpoint.h"
#include "protocol/token_file.h"

namespace {

bool write_port_file(const std::filesystem::path& path, uint16_t port) {
    auto tmp = path;
    tmp += ".tmp";
    {
        std::ofstream out(tmp);
        if (!(out << port << "\n")) return false;
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    return !ec;
}

// The command line's values, before they are checked into ServerOptions.
struct ServerFlags {
    std::string listen = "127.0.0.1:0";
    std::string port_file;
    std::string token_file;
    std::string tls_cert;
    std::string tls_key;
    std::string record_dir;
    std::string radiosity_out;
    unsigned threads = 1;
    int read_timeout_ms = 30000;
    int idle_timeout_ms = 600000;
    int frame_timeout_ms = 60000;
    int connect_timeout_ms = 10000;
    uint32_t max_connections = 256;
    uint64_t memory_budget_mb = 4096;
    unsigned max_bake_seconds = 600;
    unsigned max_concurrent_bakes = 0;
    int bake_nice = 10;
    bool quiet = false;
    bool print_config = false;
    lc::bake::MpiLaunchOptions mpi;
};

void add_server_flags(CLI::App& app, ServerFlags& flags) {
    app.add_option("--listen", flags.listen, "HOST:PORT to listen on (port 0: any free port)")
        ->capture_default_str();
    app.add_option("--port-file", flags.port_file, "Write the port number to this file once listening");
    app.add_option("--threads", flags.threads, "Bake worker threads, the builders' parallel loops included")
        ->capture_default_str()
        ->check(CLI::Range(1u, 256u));
    app.add_option("--record", flags.record_dir, "Write every channel received and sent as a dump file here");
    app.add_option("--radiosity-out", flags.radiosity_out,
                   "Write each radiosity bake's patches, with their radiosity per vertex, to this PLY file");
    app.add_option("--token-file", flags.token_file,
                   "Clients must present this token (required to listen off loopback)");
    auto* cert_opt =
        app.add_option("--tls-cert", flags.tls_cert,
                       "Serve TLS with this PEM certificate chain (required to listen off loopback)");
    auto* key_opt = app.add_option("--tls-key", flags.tls_key, "PEM private key of --tls-cert");
    cert_opt->needs(key_opt);
    key_opt->needs(cert_opt);
    app.add_option("--read-timeout-ms", flags.read_timeout_ms, "Drop a peer stalled mid-frame after this long")
        ->capture_default_str()->check(CLI::PositiveNumber);
    app.add_option("--idle-timeout-ms", flags.idle_timeout_ms, "Drop a peer silent this long with nothing running")
        ->capture_default_str()->check(CLI::PositiveNumber);
    app.add_option("--frame-timeout-ms", flags.frame_timeout_ms,
                   "Drop a peer whose frame has not arrived whole this long after its first byte")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    app.add_option("--connect-timeout-ms", flags.connect_timeout_ms,
                   "Drop a peer that has not finished the TLS handshake and Hello this long after connecting")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    app.add_option("--max-connections", flags.max_connections, "Answer connections beyond this many 'server busy'")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    app.add_option("--memory-budget-mb", flags.memory_budget_mb,
                   "MiB of channels, stored scenes and running bakes' estimated peaks over all connections; "
                   "beyond: 'server busy' (or 'too large' for a bake that could never fit)")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    app.add_option("--max-bake-seconds", flags.max_bake_seconds,
                   "Stop a bake still running this many seconds after its request, with an error saying so")
        ->capture_default_str()
        ->check(CLI::Range(1u, 7u * 24u * 3600u));
    app.add_option("--max-concurrent-bakes", flags.max_concurrent_bakes,
                   "Big bakes run at once (small ones have a lane of their own); 0: one per --threads cores, "
                   "at most one per 256 MiB of --memory-budget-mb")
        ->capture_default_str()
        ->check(CLI::Range(0u, 256u));
    app.add_option("--bake-nice", flags.bake_nice,
                   "Nice value of the bake threads, so connections and status requests are answered "
                   "first on a busy machine; 0: the server's own")
        ->capture_default_str()
        ->check(CLI::Range(0, 19));
    app.add_flag("--quiet", flags.quiet, "Log warnings and errors only");
    lc::bake::add_mpi_flags(app, flags.mpi);
    // A service keeps every flag in one file (packaging/lightmass_server.conf); the command line wins.
    app.set_config("--config", "", "Read flags from this file (TOML: flag = value, one a line)");
    app.add_flag("--print-config", flags.print_config,
                  "Print every flag with its value as a --config file, and exit")
        ->configurable(false);
}

// The checked options, or the exit status of a command line that names a problem.
std::variant<lc::bake::ServerOptions, int> server_options(const ServerFlags& flags) {
    lc::bake::ServerOptions options;
    const lc::Result<lc::Endpoint> listen = lc::parse_endpoint(flags.listen);
    if (!listen) {
        std::cerr << "error: --listen: " << listen.error() << "\n";
        return 2;
    }
    options.host = listen.value().host;
    options.port = listen.value().port;
    options.bake_threads = flags.threads;
    options.record_dir = flags.record_dir;
    options.radiosity_out = flags.radiosity_out;
    options.read_timeout = std::chrono::milliseconds(flags.read_timeout_ms);
    options.idle_timeout = std::chrono::milliseconds(flags.idle_timeout_ms);
    options.frame_timeout = std::chrono::milliseconds(flags.frame_timeout_ms);
    options.connect_timeout = std::chrono::milliseconds(flags.connect_timeout_ms);
    options.max_connections = flags.max_connections;
    options.memory_budget_bytes = flags.memory_budget_mb << 20;
    options.max_bake_time = std::chrono::seconds(flags.max_bake_seconds);
    options.max_concurrent_bakes = flags.max_concurrent_bakes;
    options.bake_nice = flags.bake_nice;
    options.tls_certificate = flags.tls_cert;
    options.tls_private_key = flags.tls_key;
    options.mpi = flags.mpi;
    options.mpi.lost_hosts = std::make_shared<lc::bake::HostRoster>();  // one memory for every bake
    if (!flags.token_file.empty()) {
        auto token = lc::read_token_file(flags.token_file);
        if (!token) {
            std::cerr << "error: " << token.error() << "\n";
            return 2;
        }
        options.token = token.value();
    }
    return options;
}

// Removes what a crashed server left in the folders this one writes to, and says so.
void sweep_stale_temporaries(const lc::bake::ServerOptions& options) {
    std::error_code ec;
    std::vector<std::filesystem::path> dirs{options.record_dir,
                                            options.mpi.work_dir.empty() ? std::filesystem::temp_directory_path(ec)
                                                                         : options.mpi.work_dir};
    if (!options.radiosity_out.empty()) dirs.push_back(std::filesystem::absolute(options.radiosity_out).parent_path());
    const lc::bake::SweepReport swept = lc::bake::sweep_stale_temporaries(dirs);
    for (const std::filesystem::path& path : swept.removed)
        spdlog::warn("startup sweep: removed '{}', a temporary left by a server that did not stop cleanly",
                     path.string());
    for (const std::string& error : swept.errors) spdlog::warn("startup sweep: cannot remove {}", error);
}

// Listens, says where ("listening on HOST:PORT" first on stdout), and serves until a signal stops
// it. SIGHUP is a graceful restart: `restart` is set and the caller runs the program again.
int serve(const lc::bake::ServerOptions& options, const std::string& port_file, bool& restart) {
    sweep_stale_temporaries(options);
    lc::bake::Server server(options);
    // Handle signals before announcing the address: a launcher may stop us at once.
    lc::asio::signal_set signals(server.io(), SIGINT, SIGTERM, SIGHUP);
    signals.async_wait([&](const boost::system::error_code& ec, int signal) {
        if (ec) return;
        restart = signal == SIGHUP;
        if (restart)
            spdlog::warn("SIGHUP received: restarting (running bakes are cancelled; the config file is read again)");
        else
            spdlog::info("signal {} received: shutting down", signal);
        server.stop(restart ? "the server is restarting (SIGHUP)"
                            : "the server is shutting down (signal " + std::to_string(signal) + ")");
    });
    auto endpoint = server.listen();
    if (!endpoint) {
        std::cerr << "error: " << endpoint.error() << "\n";
        return 1;
    }
    std::string address = endpoint->address().to_string();
    if (endpoint->address().is_v6()) address = "[" + address + "]";
    if (!options.tls_certificate.empty())
        spdlog::info("TLS on every connection, certificate '{}'", options.tls_certificate.string());
    std::printf("listening on %s:%u\n", address.c_str(), static_cast<unsigned>(endpoint->port()));
    std::fflush(stdout);
    if (!port_file.empty() && !write_port_file(port_file, endpoint->port())) {
        std::cerr << "error: cannot write port file '" << port_file << "'\n";
        return 1;
    }

    server.run();
    spdlog::info("stopped");
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    // Every block of 1 MiB and more is its own mapping, given back when freed. glibc
    // otherwise raises this threshold (up to 32 MiB) after each large free, and a
    // bake's mid-sized buffers then fragment the heap: 238 MiB instead of 164 at
    // 262,144 lights, above the estimate the bake was admitted by (RELIABILITY.md).
    mallopt(M_MMAP_THRESHOLD, 1 << 20);
    // A launcher that read our address and closed the pipe must not kill us when a
    // restart (SIGHUP) prints it again: the write fails instead.
    std::signal(SIGPIPE, SIG_IGN);
    CLI::App app{"lightmass_server: builds Lightcuts light trees for editor_client"};
    app.set_version_flag("--version", std::string("lightmass_server ") + lc::kVersion);
    ServerFlags flags;
    add_server_flags(app, flags);
    CLI11_PARSE(app, argc, argv);
    if (flags.print_config) {
        std::cout << app.config_to_str(/*default_also=*/true, /*write_description=*/true);
        return 0;
    }

    spdlog::set_default_logger(spdlog::stderr_color_mt("lightmass"));
    if (lc::bake::stderr_is_journal()) lc::bake::use_journal_format(*spdlog::default_logger());
    spdlog::set_level(flags.quiet ? spdlog::level::warn : spdlog::level::info);
    std::variant<lc::bake::ServerOptions, int> options = server_options(flags);
    if (const int* status = std::get_if<int>(&options)) return *status;
    bool restart = false;
    const int status = serve(std::get<lc::bake::ServerOptions>(options), flags.port_file, restart);
    if (!restart) return status;
    // Every socket and bake thread is gone with the server: the same program, same
    // command line and same PID (systemd's ExecReload sees no exit) starts afresh.
    execv("/proc/self/exe", argv);
    spdlog::error("restart failed: cannot run /proc/self/exe again: {}", std::strerror(errno));
    return 1;
}

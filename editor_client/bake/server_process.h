#pragma once
// A lightmass_server started by the client for --spawn-server: found next to
// the editor_client binary (or at $LC_SERVER_BIN), bound to loopback on a free
// port read from its first output line, and stopped with SIGTERM when done.
#include <sys/types.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "lightcuts/result.h"

namespace lc::client {

class ServerProcess {
public:
    // `server_flags`: the server's own flags after its address and threads (spawned_server_flags).
    static Result<std::unique_ptr<ServerProcess>> spawn(unsigned threads = 1,
                                                        const std::vector<std::string>& server_flags = {});
    // Starts `binary` with `args` (tests use it for tokens, timeouts, recording).
    static Result<std::unique_ptr<ServerProcess>> spawn_with(const std::string& binary,
                                                              const std::vector<std::string>& args);
    // Sends SIGTERM and waits; returns the exit status (or -1 when killed).
    int terminate();
    ~ServerProcess();
    ServerProcess(const ServerProcess&) = delete;
    ServerProcess& operator=(const ServerProcess&) = delete;

    const std::string& address() const { return address_; }  // "127.0.0.1:PORT"
    pid_t pid() const { return pid_; }

private:
    ServerProcess(pid_t pid, std::string address) : pid_(pid), address_(std::move(address)) {}
    pid_t pid_;
    std::string address_;
};

// What a spawned server is told for a bake over `ranks` MPI ranks: enough
// --mpi-max-ranks for them, then the user's --server-arg flags (which win).
std::vector<std::string> spawned_server_flags(uint32_t ranks, const std::vector<std::string>& server_args);

// The lightmass_server binary next to this executable, or $LC_SERVER_BIN.
std::string locate_server_binary();

}  // namespace lc::client

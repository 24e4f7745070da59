#pragma once
// Which host an MPI job lost, read from mpirun's log (Open MPI 4.1's own
// messages, and ssh's when ssh is the remote shell), as one line a user can
// act on instead of the log's many. A bake over several machines fails this
// way when a host's network or the host itself goes away, or a rank dies there.
#include <optional>
#include <string>
#include <string_view>

namespace lc::bake {

struct HostFault {
    std::string host;
    std::string text;        // one line that names the host
    bool host_lost = false;  // the host itself stopped answering (not just a rank on it)
};

// The first fault the log names a host for, or nothing.
std::optional<HostFault> host_fault_in_log(std::string_view log);

}  // namespace lc::bake

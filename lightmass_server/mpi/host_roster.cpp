#include "lightmass_server/mpi/host_roster.h"

#include <algorithm>
#include <fstream>
#include <sstream>

namespace lc::bake {

std::string host_of_hostfile_line(const std::string& line) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string host;
    words >> host;
    return host;
}

void HostRoster::mark_lost(const std::string& host, Clock::time_point now) {
    std::lock_guard lock(mutex_);
    lost_[host] = now;
}

std::vector<std::string> HostRoster::lost_at(Clock::time_point now) const {
    std::lock_guard lock(mutex_);
    std::vector<std::string> hosts;
    for (const auto& [host, when] : lost_)
        if (now - when < pause_) hosts.push_back(host);
    return hosts;
}

Result<std::string> HostRoster::hostfile_without_lost(const std::filesystem::path& hostfile,
                                                      Clock::time_point now) const {
    std::ifstream in(hostfile);
    if (!in) return make_error("cannot read the MPI host file " + hostfile.string() + " (--mpi-hostfile)");
    const std::vector<std::string> lost = lost_at(now);
    std::string kept;
    size_t hosts_kept = 0;
    for (std::string line; std::getline(in, line);) {
        const std::string host = host_of_hostfile_line(line);
        if (!host.empty() && std::find(lost.begin(), lost.end(), host) != lost.end()) continue;
        hosts_kept += host.empty() ? 0 : 1;
        kept += line + "\n";
    }
    if (hosts_kept == 0) {
        std::string names;
        for (const std::string& host : lost) names += (names.empty() ? "" : ", ") + host;
        return make_error("no host of " + hostfile.string() + " is left to bake on" +
                          (names.empty() ? std::string(": it names none")
                                         : ": lost in earlier bakes, and left out for a while: " + names));
    }
    return kept;
}

}  // namespace lc::bake

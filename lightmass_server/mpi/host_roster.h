#pragma once
// The hosts of the server's host file (--mpi-hostfile) that a bake lost: a
// host whose network or machine went down mid-bake, or that never answered.
// Later bakes leave such a host out for a while (`pause`), so the bake after a
// loss runs on the hosts that remain instead of failing on the same host
// again; past the pause the host is tried again. Shared by every bake of one
// server (MpiLaunchOptions::lost_hosts); safe from several bakes at once.
#include <chrono>
#include <filesystem>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "lightcuts/result.h"

namespace lc::bake {

// The host a line of an Open MPI host file names ("node1 slots=4 # rack 2"), or empty.
std::string host_of_hostfile_line(const std::string& line);

class HostRoster {
public:
    using Clock = std::chrono::steady_clock;
    static constexpr std::chrono::minutes kDefaultPause{10};

    explicit HostRoster(Clock::duration pause = kDefaultPause) : pause_(pause) {}

    void mark_lost(const std::string& host, Clock::time_point now = Clock::now());
    // The hosts lost within the pause before `now`, in name order.
    std::vector<std::string> lost_at(Clock::time_point now = Clock::now()) const;
    // The host file's text without the lines of lost hosts; an error names the
    // file when it cannot be read, and the lost hosts when none remains.
    Result<std::string> hostfile_without_lost(const std::filesystem::path& hostfile,
                                              Clock::time_point now = Clock::now()) const;
    Clock::duration pause() const { return pause_; }

private:
    mutable std::mutex mutex_;
    std::map<std::string, Clock::time_point> lost_;  // host -> when it was lost
    Clock::duration pause_;
};

}  // namespace lc::bake

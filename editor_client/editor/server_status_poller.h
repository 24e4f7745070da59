#pragma once
// The editor's server panel: what it says (lines from a StatusReply, or one
// line saying why there is none) and the thread that asks the server every few
// seconds, so a slow or unreachable server never holds up a frame.
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <stop_token>
#include <string>
#include <thread>
#include <vector>

#include "editor_client/bake/server_status.h"
#include "protocol/messages.h"

namespace lc::client {

// The panel's lines for a reply: version and uptime, connections, bakes with
// their progress, the memory budget held and free, the limits, MPI.
std::vector<std::string> server_panel_lines(const StatusReplyMsg& status);
// The panel's one line for a query that failed: refused (token, version) or unreachable.
std::string server_panel_error_line(const std::string& server, const std::string& error);

class ServerStatusPoller {
public:
    // Asks `query.server` at once, then every `interval`, until destroyed.
    ServerStatusPoller(ServerStatusQuery query, std::chrono::milliseconds interval);
    ~ServerStatusPoller();
    ServerStatusPoller(const ServerStatusPoller&) = delete;
    ServerStatusPoller& operator=(const ServerStatusPoller&) = delete;

    const std::string& server() const { return query_.server; }
    // The latest answer's lines; "asking HOST:PORT..." before the first.
    std::vector<std::string> lines() const;
    // Answers received (replies and failures), for tests that wait for one.
    uint64_t answers() const;
    // The lines once at least one answer came (waits for the first: at most the query's timeout).
    std::vector<std::string> answered_lines();

private:
    void poll(std::stop_token stop);

    const ServerStatusQuery query_;
    const std::chrono::milliseconds interval_;
    mutable std::mutex mutex_;
    std::condition_variable_any wake_;  // the poll thread's wait between queries
    std::condition_variable answered_;  // answered_lines()' wait for the first answer
    std::vector<std::string> lines_;
    uint64_t answers_ = 0;
    std::jthread thread_;  // last: started after the members it uses
};

}  // namespace lc::client

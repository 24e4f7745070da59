#include "editor_client/editor/server_status_poller.h"

#include <sstream>

#include "editor_client/report/server_status_report.h"

namespace lc::client {

std::vector<std::string> server_panel_lines(const StatusReplyMsg& status) {
    std::vector<std::string> lines;
    std::istringstream text(server_status_text(status));
    for (std::string line; std::getline(text, line);) lines.push_back(line);
    return lines;
}

std::string server_panel_error_line(const std::string& server, const std::string& error) {
    // query_server_status says "the server refused: ..." for a refusal (token, version); anything
    // else, "Connection refused" included, never reached a lightmass_server.
    if (error.find("the server refused: ") != std::string::npos) return "server " + server + ": " + error;
    return "server " + server + " unreachable: " + error;
}

ServerStatusPoller::ServerStatusPoller(ServerStatusQuery query, std::chrono::milliseconds interval)
    : query_(std::move(query)),
      interval_(interval),
      lines_{"asking " + query_.server + "..."},
      thread_([this](std::stop_token stop) { poll(stop); }) {}

ServerStatusPoller::~ServerStatusPoller() {
    thread_.request_stop();  // wakes the wait; a query in flight ends at its own deadline
}

std::vector<std::string> ServerStatusPoller::lines() const {
    std::lock_guard lock(mutex_);
    return lines_;
}

uint64_t ServerStatusPoller::answers() const {
    std::lock_guard lock(mutex_);
    return answers_;
}

std::vector<std::string> ServerStatusPoller::answered_lines() {
    std::unique_lock lock(mutex_);
    answered_.wait(lock, [&] { return answers_ > 0; });
    return lines_;
}

void ServerStatusPoller::poll(std::stop_token stop) {
    while (!stop.stop_requested()) {
        Result<StatusReplyMsg> status = query_server_status(query_);
        std::vector<std::string> lines =
            status ? server_panel_lines(status.value())
                   : std::vector{server_panel_error_line(query_.server, status.error())};
        std::unique_lock lock(mutex_);
        lines_ = std::move(lines);
        ++answers_;
        answered_.notify_all();
        wake_.wait_for(lock, stop, interval_, [] { return false; });
    }
}

}  // namespace lc::client

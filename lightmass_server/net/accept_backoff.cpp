#include "lightmass_server/net/accept_backoff.h"

#include <algorithm>

namespace lc::bake {

AcceptRetry AcceptBackoff::on_failure(const std::string& error, Clock::time_point now) {
    ++failures_;
    ++unlogged_;
    delay_ = delay_.count() == 0 ? kFirstAcceptRetry : std::min(delay_ * 2, kMaxAcceptRetry);
    AcceptRetry retry{delay_, std::nullopt};
    if (!last_log_ || now - *last_log_ >= kAcceptLogInterval) {
        retry.log_line = "accept failed: " + error + " (" + std::to_string(unlogged_) +
                         (unlogged_ == 1 ? " failure" : " failures") + " since the last report; retrying in " +
                         std::to_string(delay_.count()) + " ms)";
        last_log_ = now;
        unlogged_ = 0;
    }
    return retry;
}

std::optional<std::string> AcceptBackoff::on_success() {
    std::optional<std::string> line;
    if (failures_ > 0)
        line = "accepting again after " + std::to_string(failures_) + " failed accepts";
    delay_ = std::chrono::milliseconds{0};
    failures_ = 0;
    unlogged_ = 0;
    last_log_.reset();
    return line;
}

}  // namespace lc::bake

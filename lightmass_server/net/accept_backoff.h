#pragma once
// What the accept loop does after a failed accept (out of file descriptors,
// most often): wait before the next try, longer each time up to a cap, and log
// one line now and then instead of one per failure (a loop retrying at once
// spins a core and writes hundreds of thousands of lines a second).
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>

namespace lc::bake {

inline constexpr std::chrono::milliseconds kFirstAcceptRetry{10};
inline constexpr std::chrono::milliseconds kMaxAcceptRetry{1000};
inline constexpr std::chrono::seconds kAcceptLogInterval{10};

struct AcceptRetry {
    std::chrono::milliseconds delay;
    std::optional<std::string> log_line;  // at most one per kAcceptLogInterval
};

class AcceptBackoff {
public:
    using Clock = std::chrono::steady_clock;

    AcceptRetry on_failure(const std::string& error, Clock::time_point now);
    // After a successful accept: a line saying the failures are over, when there were any.
    std::optional<std::string> on_success();

private:
    std::chrono::milliseconds delay_{0};
    uint64_t failures_ = 0;       // since the last success
    uint64_t unlogged_ = 0;       // failures not yet counted in a log line
    std::optional<Clock::time_point> last_log_;
};

}  // namespace lc::bake

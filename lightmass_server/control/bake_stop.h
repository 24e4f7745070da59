#pragma once
// Why a running bake must stop, polled from the heavy stages' inner loops on
// any thread: a cancel (the client's Cancel, its disconnect, the server
// stopping) or the bake's deadline (--max-bake-seconds). A poll is one
// relaxed load and, every kClockEvery polls, a clock read, so the loops ask
// often (every few hundred rays) and stop within milliseconds.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>

#include "lightcuts/result.h"

namespace lc::bake {

class BakeStop {
public:
    using Clock = std::chrono::steady_clock;

    BakeStop() = default;
    // A bake that must end by `deadline`; `limit_text` names the limit in the error.
    BakeStop(Clock::time_point deadline, std::string limit_text)
        : deadline_(deadline), limit_text_(std::move(limit_text)) {}
    BakeStop(const BakeStop&) = delete;
    BakeStop& operator=(const BakeStop&) = delete;

    void cancel() { cancelled_.store(true, std::memory_order_relaxed); }
    bool cancelled() const { return cancelled_.load(std::memory_order_relaxed); }
    bool deadline_passed() const { return Clock::now() >= deadline_; }
    // Thread-safe; reads the clock.
    bool requested() const { return cancelled() || deadline_passed(); }
    // The error a stage returns when it stopped: kCancelled, or the deadline's
    // kFailed naming the limit.
    Error reason(const std::string& stage) const;

private:
    std::atomic<bool> cancelled_{false};
    Clock::time_point deadline_ = Clock::time_point::max();
    std::string limit_text_;
};

// One loop's (one task's) view of a BakeStop: cheap to ask every iteration.
// A null stop never stops.
class StopPoll {
public:
    static constexpr uint32_t kClockEvery = 64;

    explicit StopPoll(const BakeStop* stop) : stop_(stop) {}
    bool operator()() {
        if (!stop_ || stopped_) return stopped_;
        if (stop_->cancelled() || (++count_ % kClockEvery == 0 && stop_->deadline_passed())) stopped_ = true;
        return stopped_;
    }
    // Asks the clock now: for loops whose iterations are long (a sort's run).
    bool now() {
        if (stop_ && !stopped_ && stop_->requested()) stopped_ = true;
        return stopped_;
    }

private:
    const BakeStop* stop_;
    uint32_t count_ = 0;
    bool stopped_ = false;
};

inline bool stop_requested(const BakeStop* stop) {
    return stop && stop->requested();
}

}  // namespace lc::bake

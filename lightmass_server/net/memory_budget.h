#pragma once
// One budget of bytes for every connection's scene channels and stored
// scenes (--memory-budget-mb): a channel that does not fit is refused as
// "server busy" instead of the server running out of memory. Reservations
// are move-only and give their bytes back when destroyed.
#include <atomic>
#include <cstdint>
#include <utility>

namespace lc::bake {

class MemoryBudget {
public:
    explicit MemoryBudget(uint64_t limit_bytes) : limit_(limit_bytes) {}
    MemoryBudget(const MemoryBudget&) = delete;
    MemoryBudget& operator=(const MemoryBudget&) = delete;

    // Thread-safe. False (and nothing reserved) when `bytes` do not fit.
    bool try_reserve(uint64_t bytes);
    void release(uint64_t bytes) { used_.fetch_sub(bytes); }
    uint64_t used() const { return used_.load(); }
    uint64_t limit() const { return limit_; }

private:
    const uint64_t limit_;
    std::atomic<uint64_t> used_{0};
};

class BudgetReservation {
public:
    BudgetReservation() = default;
    // Null budget: unlimited, nothing to give back.
    BudgetReservation(MemoryBudget* budget, uint64_t bytes) : budget_(budget), bytes_(bytes) {}
    BudgetReservation(BudgetReservation&& other) noexcept { *this = std::move(other); }
    BudgetReservation& operator=(BudgetReservation&& other) noexcept;
    BudgetReservation(const BudgetReservation&) = delete;
    BudgetReservation& operator=(const BudgetReservation&) = delete;
    ~BudgetReservation() { reset(); }

    void reset();
    uint64_t bytes() const { return bytes_; }

private:
    MemoryBudget* budget_ = nullptr;
    uint64_t bytes_ = 0;
};

}  // namespace lc::bake

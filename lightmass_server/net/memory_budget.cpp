#include "lightmass_server/net/memory_budget.h"

#include <utility>

namespace lc::bake {

bool MemoryBudget::try_reserve(uint64_t bytes) {
    uint64_t used = used_.load();
    do {
        if (bytes > limit_ || used > limit_ - bytes) return false;
    } while (!used_.compare_exchange_weak(used, used + bytes));
    return true;
}

BudgetReservation& BudgetReservation::operator=(BudgetReservation&& other) noexcept {
    if (this != &other) {
        reset();
        budget_ = std::exchange(other.budget_, nullptr);
        bytes_ = std::exchange(other.bytes_, 0);
    }
    return *this;
}

void BudgetReservation::reset() {
    if (budget_) budget_->release(bytes_);
    budget_ = nullptr;
    bytes_ = 0;
}

}  // namespace lc::bake

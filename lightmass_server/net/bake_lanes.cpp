#include "lightmass_server/net/bake_lanes.h"

#include <algorithm>

namespace lc::bake {

BakeLanes::BakeLanes(unsigned concurrent_bakes)
    : concurrent_bakes_(std::max(1u, concurrent_bakes)), large_(concurrent_bakes_), small_(1) {}

void BakeLanes::join() {
    large_.join();
    small_.join();
}

unsigned default_concurrent_bakes(unsigned hardware_threads, unsigned bake_threads, uint64_t budget_bytes) {
    const uint64_t by_cores = std::max(1u, hardware_threads) / std::max(1u, bake_threads);
    const uint64_t by_budget = budget_bytes / (uint64_t{256} << 20);
    return unsigned(std::max<uint64_t>(1, std::min(by_cores, by_budget)));
}

}  // namespace lc::bake

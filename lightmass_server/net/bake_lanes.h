#pragma once
// Where bakes run. Big bakes share a pool sized from the cores and the
// memory budget (--max-concurrent-bakes); small ones (bake_footprint.h's
// kSmallBakeBytes, no indirect light) have a lane of their own, so a
// 20-light bake does not wait behind a 10^9-path one. Each bake's memory is
// reserved before it is queued, so a pool's threads never overcommit it.
#include <memory>

#include "protocol/asio.h"

namespace lc::bake {

class BakeLanes {
public:
    explicit BakeLanes(unsigned concurrent_bakes);

    asio::thread_pool& lane(bool small) { return small ? small_ : large_; }
    unsigned concurrent_bakes() const { return concurrent_bakes_; }
    // Waits for the bakes running and queued (stop them first).
    void join();

private:
    unsigned concurrent_bakes_;
    asio::thread_pool large_;
    asio::thread_pool small_;
};

// The default --max-concurrent-bakes: a bake per `bake_threads` cores, and
// no more than one per 256 MB of the budget; at least one.
unsigned default_concurrent_bakes(unsigned hardware_threads, unsigned bake_threads, uint64_t budget_bytes);

}  // namespace lc::bake

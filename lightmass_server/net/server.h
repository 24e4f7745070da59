#pragma once
// The bake server: accepts TCP connections (TLS when given a certificate) on
// one I/O thread, runs bakes on a worker pool, stops cleanly on stop() (which
// SIGINT/SIGTERM call in main).
#include <tbb/global_control.h>

#include <chrono>
#include <memory>
#include <vector>

#include "lightcuts/result.h"
#include "lightmass_server/control/bake_priority.h"
#include "lightmass_server/net/bake_lanes.h"
#include "lightmass_server/net/connection.h"
#include "lightmass_server/net/memory_budget.h"
#include "lightmass_server/net/server_options.h"
#include "protocol/asio.h"
#include "protocol/channel_recorder.h"
#include "protocol/transport.h"

namespace lc::bake {

class Server {
public:
    explicit Server(ServerOptions options);
    ~Server();

    // Loads the TLS certificate and key, binds and listens. Refuses a
    // non-loopback address without both a token and TLS.
    Result<tcp::endpoint> listen();
    // Serves until stop(); call from one thread.
    void run();
    // Thread-safe: closes the acceptor, cancels bakes, tells each peer `reason`,
    // and closes every connection once told (or after a short grace).
    void stop(const std::string& reason = "the server is shutting down");

    asio::io_context& io() { return io_; }

private:
    awaitable<void> accept_loop();
    // Waits until every connection has closed (at most kStopGrace), then stops the I/O.
    awaitable<void> close_after_grace();
    // A StatusRequest's answer: every connection's bake, the budget, the limits. On the I/O thread.
    StatusReplyMsg status() const;

    ServerOptions options_;
    // The builders' TBB loops share the bake threads' budget: --threads 1 is one
    // thread in all (TBB would otherwise add a worker per core).
    tbb::global_control bake_parallelism_;
    BakeWorkerPriority bake_worker_priority_;
    // Declared before io_: connections still queued on io_ at destruction use it.
    std::shared_ptr<asio::ssl::context> tls_context_;  // null: plain TCP
    // Before io_ too: connections destroyed with io_'s queued work give their bytes back to it.
    MemoryBudget memory_budget_;
    asio::io_context io_;
    BakeLanes workers_;
    tcp::acceptor acceptor_;
    ChannelRecorder recorder_;
    std::vector<std::weak_ptr<Connection>> connections_;
    uint64_t next_connection_id_ = 1;
    std::chrono::steady_clock::time_point started_ = std::chrono::steady_clock::now();
};

}  // namespace lc::bake

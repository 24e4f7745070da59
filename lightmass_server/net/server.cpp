#include "lightmass_server/net/server.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <thread>

#include "lightcuts/version.h"
#include "lightmass_server/net/accept_backoff.h"
#include "protocol/tls_context.h"

namespace lc::bake {
namespace {

// How long a stopping server waits for its peers to be told why.
constexpr auto kStopGrace = std::chrono::milliseconds(1000);

}  // namespace

Server::Server(ServerOptions options)
    : options_(std::move(options)),
      bake_parallelism_(tbb::global_control::max_allowed_parallelism, std::max(1u, options_.bake_threads)),
      bake_worker_priority_(options_.bake_nice),
      memory_budget_(options_.memory_budget_bytes),
      workers_(options_.max_concurrent_bakes != 0
                   ? options_.max_concurrent_bakes
                   : default_concurrent_bakes(std::thread::hardware_concurrency(), options_.bake_threads,
                                              options_.memory_budget_bytes)),
      acceptor_(io_),
      recorder_(options_.record_dir) {}

Server::~Server() {
    stop();
    workers_.join();
}

Result<tcp::endpoint> Server::listen() {
    if (Status secure = check_server_security(options_); !secure) return make_error(secure.error());
    if (!options_.tls_certificate.empty()) {
        auto context = make_tls_server_context(options_.tls_certificate, options_.tls_private_key);
        if (!context) return make_error(context.error());
        tls_context_ = std::move(context.value());
    }
    boost::system::error_code ec;
    tcp::resolver resolver(io_);
    auto endpoints = resolver.resolve(options_.host, std::to_string(options_.port), ec);
    if (ec || endpoints.empty())
        return make_error("cannot resolve listen address '" + options_.host + "': " + ec.message());
    tcp::endpoint endpoint = endpoints.begin()->endpoint();
    acceptor_.open(endpoint.protocol(), ec);
    if (!ec) acceptor_.set_option(tcp::acceptor::reuse_address(true), ec);
    if (!ec) acceptor_.bind(endpoint, ec);
    if (!ec) acceptor_.listen(asio::socket_base::max_listen_connections, ec);
    if (ec)
        return make_error("cannot listen on " + options_.host + ":" + std::to_string(options_.port) + ": " +
                          ec.message());
    return acceptor_.local_endpoint();
}

void Server::run() {
    asio::co_spawn(io_, accept_loop(), asio::detached);
    io_.run();
}

void Server::stop(const std::string& reason) {
    asio::post(io_, [this, reason] {
        boost::system::error_code ignored;
        acceptor_.close(ignored);
        for (auto& weak : connections_)
            if (auto connection = weak.lock()) connection->stop_serving(reason);
        asio::co_spawn(io_, close_after_grace(), asio::detached);
    });
}

awaitable<void> Server::close_after_grace() {
    asio::steady_timer timer(io_);
    const auto deadline = std::chrono::steady_clock::now() + kStopGrace;
    auto open = [this] {
        return std::any_of(connections_.begin(), connections_.end(), [](const std::weak_ptr<Connection>& weak) {
            const auto connection = weak.lock();
            return connection && !connection->closed();
        });
    };
    while (open() && std::chrono::steady_clock::now() < deadline) {
        timer.expires_after(std::chrono::milliseconds(10));
        boost::system::error_code ec;
        co_await timer.async_wait(asio::redirect_error(asio::use_awaitable, ec));
    }
    for (auto& weak : connections_)
        if (auto connection = weak.lock()) connection->close("server shutting down");
    connections_.clear();
    io_.stop();
}

StatusReplyMsg Server::status() const {
    StatusReplyMsg reply;
    reply.version = std::string("lightmass_server ") + kVersion;
    reply.uptime_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
    for (const auto& weak : connections_) {
        const auto connection = weak.lock();
        if (!connection || connection->closed()) continue;
        ++reply.connections;
        if (std::optional<BakeStatusEntry> bake = connection->bake_status()) reply.bakes.push_back(*bake);
    }
    reply.memory_budget_bytes = memory_budget_.limit();
    reply.memory_held_bytes = memory_budget_.used();
    reply.max_connections = options_.max_connections;
    reply.max_concurrent_bakes = workers_.concurrent_bakes();
    reply.max_bake_seconds = uint32_t(options_.max_bake_time.count());
    reply.mpi_launcher = options_.mpi.launcher;
    reply.mpi_max_ranks = options_.mpi.max_ranks;
    return reply;
}

awaitable<void> Server::accept_loop() {
    AcceptBackoff backoff;
    asio::steady_timer retry_timer(io_);
    while (acceptor_.is_open()) {
        boost::system::error_code ec;
        tcp::socket socket = co_await acceptor_.async_accept(asio::redirect_error(asio::use_awaitable, ec));
        if (ec) {
            if (!acceptor_.is_open()) co_return;
            AcceptRetry retry = backoff.on_failure(ec.message(), AcceptBackoff::Clock::now());
            if (retry.log_line) spdlog::warn("{}", *retry.log_line);
            retry_timer.expires_after(retry.delay);
            co_await retry_timer.async_wait(asio::redirect_error(asio::use_awaitable, ec));
            continue;
        }
        if (std::optional<std::string> recovered = backoff.on_success()) spdlog::info("{}", *recovered);
        socket.set_option(tcp::no_delay(true), ec);
        std::erase_if(connections_, [](const std::weak_ptr<Connection>& w) { return w.expired(); });
        size_t open = 0;
        for (auto& weak : connections_)
            if (auto connection = weak.lock(); connection && !connection->closed()) ++open;
        std::string busy_reason;
        if (open >= options_.max_connections)
            busy_reason = std::to_string(open) + " connections open, the limit (--max-connections)";
        Transport transport = tls_context_ ? Transport::tls(std::move(socket), *tls_context_)
                                           : Transport::plain(std::move(socket));
        auto connection = std::make_shared<Connection>(std::move(transport), options_, workers_, recorder_,
                                                       next_connection_id_++, memory_budget_,
                                                       std::move(busy_reason), [this] { return status(); });
        connections_.push_back(connection);
        connection->start();
    }
}

}  // namespace lc::bake

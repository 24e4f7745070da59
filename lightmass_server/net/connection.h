#pragma once
// One client connection, the I/O layer only: it reads bytes, frames and decodes
// them, hands the messages to its ServerSession (the protocol) and carries out
// what the session answers: frames to write, bakes to start or cancel on the
// worker pool, a result to stream. Three coroutines on the server's I/O
// thread: the reader (after the TLS handshake), the writer, and one deadline
// timer that closes a peer that is too slow (the pattern of Asio's C++20
// timeout example; Boost 1.74 has no awaitable operators).
#include <atomic>
#include <chrono>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "lightmass_server/net/bake_lanes.h"
#include "lightmass_server/net/result_stream.h"
#include "lightmass_server/net/server_options.h"
#include "lightmass_server/net/server_session.h"
#include "protocol/asio.h"
#include "protocol/channel_recorder.h"
#include "protocol/encoded_frame.h"
#include "protocol/frame_decoder.h"
#include "protocol/transport.h"

namespace lc::bake {

class Connection : public std::enable_shared_from_this<Connection> {
public:
    // `busy_reason` non-empty: the server is full, this peer is told so after its Hello.
    Connection(Transport transport, const ServerOptions& options, BakeLanes& workers,
               const ChannelRecorder& recorder, uint64_t id, MemoryBudget& memory_budget,
               std::string busy_reason, std::function<StatusReplyMsg()> status = {});

    void start();
    void close(const std::string& reason);
    // Tells the peer why (its bake cancelled) and closes once that is sent.
    void stop_serving(const std::string& reason);
    bool closed() const { return closed_; }
    uint64_t id() const { return id_; }
    std::optional<BakeStatusEntry> bake_status() const { return session_.bake_status(); }

private:
    using Clock = std::chrono::steady_clock;

    // The TLS handshake (nothing for plain TCP), then the writer, then reads until the end.
    awaitable<void> serve();
    awaitable<void> read_loop();
    awaitable<void> write_loop();
    // Sleeps until the deadline; closes the connection when it passes unmoved.
    awaitable<void> watch_deadline();

    enum class DeadlineKind {
        kNone,
        kTlsHandshake,
        kHello,
        kFlush,
        kStalledFrame,
        kSlowFrame,
        kStalledChannel,
        kIdle
    };
    struct Deadline {
        Clock::time_point at = Clock::time_point::max();
        DeadlineKind kind = DeadlineKind::kNone;
    };
    // The earliest time by which the peer must have done something, and what it must have done.
    Deadline next_deadline() const;
    std::string deadline_reason(DeadlineKind kind) const;
    // The deadline may have moved earlier: wake its coroutine to look again.
    void rearm_deadline() { deadline_timer_.cancel(); }

    void apply(ServerActions actions);
    void start_bake(StartBake start);
    // Sends what is queued (an error explaining why), then closes.
    void close_after_flush(const std::string& reason);
    void wake_writer() { wake_.cancel(); }

    Transport transport_;
    const ServerOptions& options_;
    BakeLanes& workers_;
    const ChannelRecorder& recorder_;
    uint64_t id_;
    std::string peer_;

    ServerSession session_;
    FrameDecoder decoder_;
    asio::steady_timer wake_;
    asio::steady_timer deadline_timer_;
    std::deque<EncodedFrame> outbox_;
    std::optional<ResultStream> stream_;
    std::shared_ptr<BakeStop> bake_stop_;  // the running bake's; null when none
    bool closed_ = false;
    bool handshaken_ = false;  // TLS handshake done (plain TCP: at once)
    bool closing_ = false;
    std::string closing_reason_;
    Clock::time_point accepted_at_;
    Clock::time_point closing_since_;
    Clock::time_point last_read_;
    Clock::time_point frame_started_;  // first byte of the partial frame held by decoder_
};

}  // namespace lc::bake

#include "lightmass_server/net/connection.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "lightmass_server/control/bake_priority.h"
#include "lightmass_server/mpi/bake_dispatch.h"
#include "protocol/codec.h"

namespace lc::bake {
namespace {

using namespace std::chrono_literals;

constexpr auto kFlushGrace = 5s;
constexpr auto kTlsShutdownGrace = std::chrono::milliseconds(1000);
constexpr auto kProgressInterval = 100ms;

auto ec_token(boost::system::error_code& ec) { return asio::redirect_error(asio::use_awaitable, ec); }

template <class... Ts>
struct Overloaded : Ts... {
    using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;


}  // namespace

Connection::Connection(Transport transport, const ServerOptions& options, BakeLanes& workers,
                       const ChannelRecorder& recorder, uint64_t id, MemoryBudget& memory_budget,
                       std::string busy_reason, std::function<StatusReplyMsg()> status)
    : transport_(std::move(transport)),
      options_(options),
      workers_(workers),
      recorder_(recorder),
      id_(id),
      session_(ServerSessionOptions{id, options.token, recorder.enabled(), std::move(busy_reason),
                                    &memory_budget, options.memory_budget_bytes / 2, std::move(status)}),
      decoder_(options.max_frame_bytes),
      wake_(transport_.get_executor()),
      deadline_timer_(transport_.get_executor()) {
    boost::system::error_code ec;
    auto remote = transport_.lowest_layer().remote_endpoint(ec);
    peer_ = ec ? "unknown peer" : remote.address().to_string() + ":" + std::to_string(remote.port());
}

void Connection::start() {
    accepted_at_ = last_read_ = Clock::now();
    spdlog::info("connection {}: accepted from {}{}", id_, peer_, transport_.is_tls() ? " (TLS)" : "");
    auto self = shared_from_this();
    asio::co_spawn(transport_.get_executor(), [self] { return self->serve(); }, asio::detached);
    asio::co_spawn(transport_.get_executor(), [self] { return self->watch_deadline(); }, asio::detached);
}

awaitable<void> Connection::serve() {
    boost::system::error_code ec = co_await transport_.handshake(TransportRole::kServer);
    if (closed_) co_return;
    if (ec) {
        // A plain client, a client that does not trust our certificate, or a
        // scanner: only this connection ends.
        std::string reason = "TLS handshake with " + peer_ + " failed: " + transport_.handshake_error_text(ec);
        spdlog::warn("connection {}: {}", id_, reason);
        close(reason);
        co_return;
    }
    handshaken_ = true;
    last_read_ = Clock::now();
    rearm_deadline();
    auto self = shared_from_this();
    asio::co_spawn(transport_.get_executor(), [self] { return self->write_loop(); }, asio::detached);
    co_await read_loop();
}

void Connection::close(const std::string& reason) {
    if (closed_) return;
    closed_ = true;
    spdlog::info("connection {}: closed ({})", id_, reason);
    session_.on_closing();
    if (bake_stop_) bake_stop_->cancel();  // a client that disconnects cancels its bake
    stream_.reset();
    transport_.close();
    wake_.cancel();
    deadline_timer_.cancel();
}

void Connection::stop_serving(const std::string& reason) {
    if (closed_) return;
    apply(session_.on_server_stopping(reason));
}

void Connection::close_after_flush(const std::string& reason) {
    if (closing_ || closed_) return;
    closing_ = true;
    closing_reason_ = reason;
    closing_since_ = Clock::now();
    apply(session_.on_closing());
    if (bake_stop_) bake_stop_->cancel();
    wake_writer();
    rearm_deadline();
}

void Connection::apply(ServerActions actions) {
    for (ServerAction& action : actions) {
        std::visit(Overloaded{
                       [&](SendMessage& send) {
                           if (closed_) return;
                           outbox_.push_back(encode_frame_in_place(send.message));
                           wake_writer();
                       },
                       [&](StartBake& start) { start_bake(std::move(start)); },
                       [&](CancelBake&) {
                           if (bake_stop_) bake_stop_->cancel();
                       },
                       [&](StreamResult& result) {
                           if (result.file)
                               stream_.emplace(std::move(result.file), result.channel_id,
                                               std::move(result.done), kDefaultChunkBytes);
                           else
                               stream_.emplace(std::move(result.tree), result.channel_id,
                                               std::move(result.done), kDefaultChunkBytes);
                           wake_writer();
                       },
                       [&](StopStream&) { stream_.reset(); },
                       [&](RecordChannel& record) {
                           Status recorded = recorder_.record(record.name, record.bytes);
                           if (!recorded)
                               spdlog::warn("connection {}: recording failed: {}", id_, recorded.error());
                       },
                       [&](CloseAfterFlush& close) { close_after_flush(close.reason); },
                   },
                   action);
    }
    rearm_deadline();
}

void Connection::start_bake(StartBake start) {
    start.inputs.raycast_threads = int(std::max(1u, options_.bake_threads));
    start.inputs.radiosity_out = options_.radiosity_out.string();
    start.inputs.mpi = options_.mpi;
    auto stop =
        std::make_shared<BakeStop>(Clock::now() + options_.max_bake_time,
                                   "--max-bake-seconds " + std::to_string(options_.max_bake_time.count()) +
                                       " (the server's limit on one bake's time)");
    start.inputs.stop = stop;
    bake_stop_ = stop;
    auto self = shared_from_this();
    auto executor = transport_.get_executor();
    asio::thread_pool& lane = workers_.lane(start.small);
    asio::post(lane, [self, executor, start = std::move(start), stop] {
        const uint32_t bake_id = start.bake_id;
        lower_this_thread_priority(self->options_.bake_nice);
        if (self->options_.on_bake_thread_start) self->options_.on_bake_thread_start();
        auto last_sent = Clock::now() - kProgressInterval;
        std::string last_stage;
        ProgressFn progress = [&](std::string_view stage, double percent) {
            auto now = Clock::now();
            if (stage != last_stage || now - last_sent >= kProgressInterval || percent >= 100.0) {
                last_sent = now;
                last_stage = std::string(stage);
                ProgressMsg msg{bake_id, last_stage, static_cast<float>(std::clamp(percent, 0.0, 100.0))};
                asio::post(executor, [self, msg] {
                    if (!self->closed()) self->apply(self->session_.on_bake_progress(msg));
                });
            }
            return !stop->requested();
        };
        Result<BuildResult> result = stop->requested()
                                         ? Result<BuildResult>(stop->reason("bake before its start"))
                                         : run_bake(start.inputs, progress);
        // A stage that saw only "stop" reports a cancel; the deadline is the reason to give.
        if (!result && !stop->cancelled() && stop->deadline_passed()) result = stop->reason("bake");
        asio::post(executor, [self, bake_id, stop, result = std::move(result)]() mutable {
            if (self->bake_stop_ == stop) self->bake_stop_.reset();
            if (!self->closed()) self->apply(self->session_.on_bake_finished(bake_id, std::move(result)));
        });
    });
}

awaitable<void> Connection::read_loop() {
    std::vector<uint8_t> buffer(64 * 1024);
    std::vector<std::vector<uint8_t>> frames;
    while (!closed_ && !closing_) {
        boost::system::error_code ec;
        size_t n = co_await transport_.read_some(asio::buffer(buffer), ec);
        if (ec) {
            close(is_peer_closed(ec) ? "peer closed the connection" : "read failed: " + ec.message());
            co_return;
        }
        last_read_ = Clock::now();
        frames.clear();
        const bool was_in_frame = decoder_.buffered_bytes() > 0;
        bool framing_ok = decoder_.consume({buffer.data(), n}, frames);
        // A new partial frame began in this read: its whole-frame deadline starts now.
        if (decoder_.buffered_bytes() > 0 && (!was_in_frame || !frames.empty())) frame_started_ = last_read_;
        for (auto& frame : frames) {
            Result<Message> message = decode_message(frame);
            if (!message) {
                apply(session_.on_malformed_frame(message.error()));
                co_return;
            }
            apply(session_.on_message(std::move(message.value())));
            if (closed_ || closing_) co_return;
        }
        if (!framing_ok) {
            apply(session_.on_bad_frame_header(decoder_.error()));
            co_return;
        }
        rearm_deadline();
    }
}

awaitable<void> Connection::write_loop() {
    while (!closed_) {
        std::optional<EncodedFrame> frame;
        if (!outbox_.empty()) {
            frame = std::move(outbox_.front());
            outbox_.pop_front();
        } else if (stream_ && !closing_) {
            auto next = stream_->next_frame();
            if (!next) {
                stream_.reset();
                session_.on_result_delivered();
                rearm_deadline();
                continue;
            }
            frame = std::move(next);
        } else if (closing_) {
            // TLS: close_notify, so the peer knows the error it read was the last word.
            co_await transport_.shutdown(kTlsShutdownGrace);
            close(closing_reason_);
            co_return;
        } else {
            boost::system::error_code ec;
            wake_.expires_at(Clock::time_point::max());
            co_await wake_.async_wait(ec_token(ec));
            continue;
        }
        const std::span<const uint8_t> bytes = frame->bytes();
        boost::system::error_code ec = co_await transport_.write(asio::buffer(bytes.data(), bytes.size()));
        if (ec) {
            close("write failed: " + ec.message());
            co_return;
        }
    }
}

Connection::Deadline Connection::next_deadline() const {
    Deadline next;
    auto consider = [&](Clock::time_point at, DeadlineKind kind) {
        if (at < next.at) next = Deadline{at, kind};
    };
    if (closing_) {
        consider(closing_since_ + kFlushGrace, DeadlineKind::kFlush);
        return next;
    }
    if (!handshaken_) consider(accepted_at_ + options_.read_timeout, DeadlineKind::kTlsHandshake);
    if (!session_.greeted()) consider(accepted_at_ + options_.connect_timeout, DeadlineKind::kHello);
    if (!handshaken_) return next;
    if (decoder_.buffered_bytes() > 0) {
        consider(last_read_ + options_.read_timeout, DeadlineKind::kStalledFrame);
        consider(frame_started_ + options_.frame_timeout, DeadlineKind::kSlowFrame);
    } else if (session_.receiving_channel()) {
        // Between frames of an open channel: the peer owes the rest of it, whatever its size.
        consider(last_read_ + options_.read_timeout, DeadlineKind::kStalledChannel);
    } else if (session_.idle() && !stream_) {
        consider(last_read_ + options_.idle_timeout, DeadlineKind::kIdle);
    }
    return next;
}

std::string Connection::deadline_reason(DeadlineKind kind) const {
    auto ms = [](std::chrono::milliseconds limit) { return std::to_string(limit.count()) + " ms"; };
    switch (kind) {
        case DeadlineKind::kTlsHandshake: return "TLS handshake not finished within " + ms(options_.read_timeout);
        case DeadlineKind::kHello: return "no Hello within " + ms(options_.connect_timeout) + " of connecting";
        case DeadlineKind::kFlush: return closing_reason_ + "; peer did not read the error in time";
        case DeadlineKind::kStalledFrame: return "stalled in the middle of a frame for " + ms(options_.read_timeout);
        case DeadlineKind::kSlowFrame:
            return "a frame did not arrive whole within " + ms(options_.frame_timeout) + " of its first byte";
        case DeadlineKind::kStalledChannel:
            return "sent nothing for " + ms(options_.read_timeout) + " with a channel open";
        case DeadlineKind::kIdle: return "idle for " + ms(options_.idle_timeout);
        case DeadlineKind::kNone: break;
    }
    return "deadline passed";
}

awaitable<void> Connection::watch_deadline() {
    while (!closed_) {
        const Deadline deadline = next_deadline();
        if (Clock::now() >= deadline.at) {
            close(deadline_reason(deadline.kind));
            co_return;
        }
        deadline_timer_.expires_at(deadline.at);
        boost::system::error_code ec;
        co_await deadline_timer_.async_wait(ec_token(ec));
    }
}

}  // namespace lc::bake

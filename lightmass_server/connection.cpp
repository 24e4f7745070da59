#include "lightmass_server/connection.h"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "lightmass_server/auth_token.h"
#include "protocol/channel_name.h"
#include "protocol/codec.h"

namespace lc::bake {
namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

constexpr size_t kMaxOpenChannels = 4;
constexpr size_t kMaxStoredScenes = 4;
constexpr auto kFlushGrace = 5s;
constexpr auto kTlsShutdownGrace = std::chrono::milliseconds(1000);
constexpr auto kProgressInterval = 100ms;

auto ec_token(boost::system::error_code& ec) { return asio::redirect_error(asio::use_awaitable, ec); }

}  // namespace

Connection::Connection(Transport transport, const ServerOptions& options, asio::thread_pool& workers,
                       const ChannelRecorder& recorder, uint64_t id)
    : transport_(std::move(transport)),
      options_(options),
      workers_(workers),
      recorder_(recorder),
      id_(id),
      decoder_(options.max_frame_bytes),
      wake_(transport_.get_executor()) {
    boost::system::error_code ec;
    auto remote = transport_.lowest_layer().remote_endpoint(ec);
    peer_ = ec ? "unknown peer" : remote.address().to_string() + ":" + std::to_string(remote.port());
}

void Connection::start() {
    last_read_ = Clock::now();
    spdlog::info("connection {}: accepted from {}{}", id_, peer_, transport_.is_tls() ? " (TLS)" : "");
    auto self = shared_from_this();
    asio::co_spawn(
        transport_.get_executor(), [self] { return self->handshake_then_serve(); }, asio::detached);
    asio::co_spawn(transport_.get_executor(), [self] { return self->watchdog(); }, asio::detached);
}

awaitable<void> Connection::handshake_then_serve() {
    boost::system::error_code ec = co_await transport_.handshake(TransportRole::kServer);
    if (closed_) co_return;
    if (ec) {
        // A plain client, a client that does not trust our certificate, or a
        // scanner: only this connection ends.
        std::string reason =
            "TLS handshake with " + peer_ + " failed: " + transport_.handshake_error_text(ec);
        spdlog::warn("connection {}: {}", id_, reason);
        close(reason);
        co_return;
    }
    handshaken_ = true;
    last_read_ = Clock::now();
    auto self = shared_from_this();
    asio::co_spawn(transport_.get_executor(), [self] { return self->read_loop(); }, asio::detached);
    asio::co_spawn(transport_.get_executor(), [self] { return self->write_loop(); }, asio::detached);
}

void Connection::close(const std::string& reason) {
    if (closed_) return;
    closed_ = true;
    spdlog::info("connection {}: closed ({})", id_, reason);
    if (bake_) bake_->cancel->store(true);  // a client that disconnects cancels its bake
    stream_.reset();
    transport_.close();
    wake_.cancel();
}

void Connection::close_after_flush(const std::string& reason) {
    if (closing_ || closed_) return;
    closing_ = true;
    closing_reason_ = reason;
    closing_since_ = Clock::now();
    if (bake_) bake_->cancel->store(true);
    wake_writer();
}

void Connection::send(const Message& message) {
    if (closed_) return;
    outbox_.push_back(encode_frame(message));
    wake_writer();
}

void Connection::send_error(uint32_t bake_id, ErrorCode code, const std::string& text) {
    spdlog::warn("connection {}: error sent: {}", id_, text);
    send(ErrorMsg{bake_id, code, text});
}

void Connection::wake_writer() { wake_.cancel(); }

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
        bool framing_ok = decoder_.consume({buffer.data(), n}, frames);
        for (auto& frame : frames) {
            Result<Message> message = decode_message(frame);
            if (!message) {
                send_error(0, ErrorCode::kMalformedFrame, "malformed frame: " + message.error());
                close_after_flush("malformed frame");
                co_return;
            }
            if (!handle(std::move(message.value()))) {
                close_after_flush("protocol violation");
                co_return;
            }
            if (closed_ || closing_) co_return;
        }
        if (!framing_ok) {
            send_error(0, ErrorCode::kTooLarge, "bad frame header: " + decoder_.error());
            close_after_flush("bad frame header");
            co_return;
        }
    }
}

awaitable<void> Connection::write_loop() {
    while (!closed_) {
        std::vector<uint8_t> frame;
        if (!outbox_.empty()) {
            frame = std::move(outbox_.front());
            outbox_.pop_front();
        } else if (stream_ && !closing_) {
            auto next = stream_->next_frame();
            if (!next) {
                stream_.reset();
                spdlog::info("connection {}: bake {} delivered", id_, bake_ ? bake_->bake_id : 0);
                bake_.reset();
                continue;
            }
            frame = std::move(*next);
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
        boost::system::error_code ec = co_await transport_.write(asio::buffer(frame));
        if (ec) {
            close("write failed: " + ec.message());
            co_return;
        }
    }
}

awaitable<void> Connection::watchdog() {
    asio::steady_timer timer(transport_.get_executor());
    while (!closed_) {
        boost::system::error_code ec;
        timer.expires_after(200ms);
        co_await timer.async_wait(ec_token(ec));
        if (closed_) co_return;
        auto now = Clock::now();
        auto quiet = now - last_read_;
        if (!handshaken_ && quiet > options_.read_timeout) {
            close("TLS handshake not finished within " + std::to_string(options_.read_timeout.count()) +
                  " ms");
        } else if (closing_ && now - closing_since_ > kFlushGrace) {
            close(closing_reason_ + "; peer did not read the error in time");
        } else if (decoder_.buffered_bytes() > 0 && quiet > options_.read_timeout) {
            close("stalled in the middle of a frame for " +
                  std::to_string(options_.read_timeout.count()) + " ms");
        } else if (!bake_ && !stream_ && incoming_.empty() && quiet > options_.idle_timeout) {
            close("idle for " + std::to_string(options_.idle_timeout.count()) + " ms");
        }
    }
}

bool Connection::handle(Message message) {
    if (!greeted_ && !std::holds_alternative<HelloMsg>(message)) {
        send_error(0, ErrorCode::kMalformedFrame,
                   std::string("expected Hello as the first message, got ") + message_name(message));
        return false;
    }
    if (auto* m = std::get_if<HelloMsg>(&message)) return on_hello(*m);
    if (auto* m = std::get_if<OpenChannelMsg>(&message)) return on_open_channel(*m);
    if (auto* m = std::get_if<WriteChannelMsg>(&message)) return on_write_channel(*m);
    if (auto* m = std::get_if<CloseChannelMsg>(&message)) return on_close_channel(*m);
    if (auto* m = std::get_if<BakeRequestMsg>(&message)) return on_bake_request(*m);
    if (auto* m = std::get_if<CancelMsg>(&message)) {
        if (bake_ && bake_->bake_id == m->bake_id) {
            bake_->cancel->store(true);
            if (stream_) {  // already built: stop streaming, the client discards the partial channel
                stream_.reset();
                bake_.reset();
                send_error(m->bake_id, ErrorCode::kCancelled,
                           "bake " + std::to_string(m->bake_id) + " cancelled during transfer");
            }
        }
        return true;
    }
    send_error(0, ErrorCode::kMalformedFrame,
               std::string("a client may not send ") + message_name(message) + " messages");
    return false;
}

bool Connection::on_hello(const HelloMsg& hello) {
    if (greeted_) {
        send_error(0, ErrorCode::kMalformedFrame, "Hello sent twice");
        return false;
    }
    if (hello.protocol_version != kProtocolVersion) {
        send_error(0, ErrorCode::kVersionMismatch,
                   "protocol version mismatch: client speaks " + hello.protocol_version.to_hex() +
                       ", server speaks " + kProtocolVersion.to_hex());
        return false;
    }
    if (options_.token && !tokens_equal(*options_.token, hello.token)) {
        send_error(0, ErrorCode::kAuthentication,
                   hello.token.empty() ? "this server requires a token (client: --token-file FILE)"
                                       : "authentication failed: the token does not match");
        return false;
    }
    greeted_ = true;
    spdlog::info("connection {}: hello from '{}'", id_, hello.peer_name);
    send(HelloAckMsg{kProtocolVersion, "lightmass_server 0.1.0"});
    return true;
}

bool Connection::on_open_channel(const OpenChannelMsg& open) {
    if (incoming_.count(open.channel_id) || refused_.count(open.channel_id)) {
        send_error(0, ErrorCode::kMalformedFrame,
                   "channel id " + std::to_string(open.channel_id) + " is already open");
        return false;
    }
    auto refuse = [&](ErrorCode code, const std::string& text) {
        refused_.insert(open.channel_id);
        send_error(0, code, "channel '" + open.name + "' refused: " + text);
        return true;
    };
    auto name = ChannelName::parse(open.name);
    if (!name) return refuse(ErrorCode::kUnknownChannel, "not a VERSION.GUID.ext channel name");
    if (name->extension != kSceneExtension)
        return refuse(ErrorCode::kUnknownChannel,
                      "this server accepts only ." + std::string(kSceneExtension) + " channels, got ." +
                          name->extension);
    if (name->version != kSceneFormatVersionGuid)
        return refuse(ErrorCode::kVersionMismatch,
                      "scene format version " + name->version.to_hex() + " is not supported; this server reads " +
                          kSceneFormatVersionGuid.to_hex());
    const uint64_t max_bytes = 4 + uint64_t{kMaxSceneLights} * scene_record_bytes();
    if (open.total_bytes > max_bytes)
        return refuse(ErrorCode::kTooLarge, "announces " + std::to_string(open.total_bytes) +
                                                " bytes; the limit is " + std::to_string(max_bytes) + " (" +
                                                std::to_string(kMaxSceneLights) + " lights)");
    if (incoming_.size() >= kMaxOpenChannels)
        return refuse(ErrorCode::kBusy, "too many channels open at once (limit " +
                                            std::to_string(kMaxOpenChannels) + ")");
    IncomingScene& scene = incoming_[open.channel_id];
    scene.name = open.name;
    scene.total_bytes = open.total_bytes;
    return true;
}

bool Connection::on_write_channel(WriteChannelMsg& write) {
    if (refused_.count(write.channel_id)) return true;  // already answered with an error
    auto it = incoming_.find(write.channel_id);
    if (it == incoming_.end()) {
        send_error(0, ErrorCode::kUnknownChannel,
                   "write to channel id " + std::to_string(write.channel_id) + " which is not open");
        return false;
    }
    IncomingScene& scene = it->second;
    if (write.offset != scene.received) {
        send_error(0, ErrorCode::kMalformedFrame,
                   "channel '" + scene.name + "': write at offset " + std::to_string(write.offset) +
                       ", expected " + std::to_string(scene.received));
        return false;
    }
    auto refuse = [&](const std::string& text) {
        send_error(0, ErrorCode::kInvalidScene, "scene channel '" + scene.name + "': " + text);
        refused_.insert(write.channel_id);
        incoming_.erase(it);
        return true;
    };
    if (scene.received + write.data.size() > scene.total_bytes)
        return refuse("more bytes than the " + std::to_string(scene.total_bytes) + " announced");
    Status consumed = scene.reader.consume(write.data);
    if (!consumed) return refuse(consumed.error());
    scene.received += write.data.size();
    if (recorder_.enabled()) scene.recorded.insert(scene.recorded.end(), write.data.begin(), write.data.end());
    return true;
}

bool Connection::on_close_channel(const CloseChannelMsg& close_msg) {
    if (refused_.erase(close_msg.channel_id)) return true;
    auto it = incoming_.find(close_msg.channel_id);
    if (it == incoming_.end()) {
        send_error(0, ErrorCode::kUnknownChannel,
                   "close of channel id " + std::to_string(close_msg.channel_id) + " which is not open");
        return false;
    }
    IncomingScene scene = std::move(it->second);
    incoming_.erase(it);
    if (scene.received != scene.total_bytes) {
        send_error(0, ErrorCode::kInvalidScene,
                   "scene channel '" + scene.name + "' closed after " + std::to_string(scene.received) +
                       " of " + std::to_string(scene.total_bytes) + " bytes");
        return true;
    }
    Result<std::vector<SceneLight>> lights = scene.reader.finish();
    if (!lights) {
        send_error(0, ErrorCode::kInvalidScene, "scene channel '" + scene.name + "': " + lights.error());
        return true;
    }
    if (recorder_.enabled()) {
        Status recorded = recorder_.record(scene.name, scene.recorded);
        if (!recorded) spdlog::warn("connection {}: recording failed: {}", id_, recorded.error());
    }
    spdlog::info("connection {}: scene '{}' received, {} lights", id_, scene.name, lights->size());
    if (scenes_.size() >= kMaxStoredScenes && !scenes_.count(scene.name)) scenes_.erase(scenes_.begin());
    scenes_[scene.name] = std::move(lights.value());
    return true;
}

bool Connection::on_bake_request(const BakeRequestMsg& request) {
    if (bake_) {
        send_error(request.bake_id, ErrorCode::kBusy,
                   "bake " + std::to_string(bake_->bake_id) + " is still running on this connection");
        return true;
    }
    auto scene = scenes_.find(request.scene_channel);
    if (scene == scenes_.end()) {
        send_error(request.bake_id, ErrorCode::kUnknownChannel,
                   "no complete scene channel named '" + request.scene_channel +
                       "' (open, write and close it before BakeRequest)");
        return true;
    }
    auto lights = std::make_shared<std::vector<SceneLight>>();
    size_t classic = 0;
    for (const SceneLight& light : scene->second) {
        if (light.classic) ++classic;
        else lights->push_back(light);
    }
    if (classic > 0)
        send(WarningMsg{request.bake_id, std::to_string(classic) +
                                             " classic lights in the scene channel were left out of the tree"});

    BuildOptions build;
    build.builder = request.builder;
    build.representative_rule = request.representative_rule;
    build.pairing = request.pairing;
    build.seed = request.seed;
    if (request.exact_pairing_limit != 0) build.exact_pairing_limit = request.exact_pairing_limit;

    auto cancel = std::make_shared<std::atomic<bool>>(false);
    bake_ = ActiveBake{request.bake_id, cancel};
    spdlog::info("connection {}: bake {} of {} lights with {} (seed {})", id_, request.bake_id, lights->size(),
                 builder_name(build.builder), build.seed);
    send(ProgressMsg{request.bake_id, "queued", 0.0f});

    auto self = shared_from_this();
    auto executor = transport_.get_executor();
    uint32_t bake_id = request.bake_id;
    asio::post(workers_, [self, executor, lights, build, cancel, bake_id] {
        auto last_sent = Clock::now() - kProgressInterval;
        std::string last_stage;
        ProgressFn progress = [&](std::string_view stage, double percent) {
            auto now = Clock::now();
            if (stage != last_stage || now - last_sent >= kProgressInterval || percent >= 100.0) {
                last_sent = now;
                last_stage = std::string(stage);
                ProgressMsg msg{bake_id, last_stage, static_cast<float>(std::clamp(percent, 0.0, 100.0))};
                asio::post(executor, [self, msg] {
                    if (!self->closed() && self->bake_ && self->bake_->bake_id == msg.bake_id) self->send(msg);
                });
            }
            return !cancel->load();
        };
        Result<BuildResult> result = cancel->load() ? Result<BuildResult>(make_error("cancelled before start"))
                                                    : build_light_tree(*lights, build, progress);
        asio::post(executor, [self, bake_id, result = std::move(result)]() mutable {
            self->on_bake_finished(bake_id, std::move(result));
        });
    });
    return true;
}

void Connection::on_bake_finished(uint32_t bake_id, Result<BuildResult> result) {
    if (closed_ || closing_ || !bake_ || bake_->bake_id != bake_id) return;
    if (!result) {
        bool cancelled = result.error().rfind("cancelled", 0) == 0 || bake_->cancel->load();
        if (cancelled)
            send_error(bake_id, ErrorCode::kCancelled, "bake " + std::to_string(bake_id) + " cancelled");
        else
            send_error(bake_id, ErrorCode::kBakeFailed, "bake " + std::to_string(bake_id) + " failed: " + result.error());
        bake_.reset();
        return;
    }
    BuildResult built = std::move(result.value());
    for (const std::string& warning : built.report.warnings) send(WarningMsg{bake_id, warning});
    auto tree = std::make_shared<const LightTree>(std::move(built.tree));
    BakeDoneMsg done;
    done.bake_id = bake_id;
    done.result_channel = lightcuts_result_channel_name();
    done.node_count = static_cast<uint32_t>(tree->nodes.size());
    done.leaf_count = tree->leaf_count;
    done.build_ms = built.report.build_ms;
    done.pairing_cost = built.report.pairing_cost;
    done.pairing_lower_bound = built.report.pairing_lower_bound;
    done.exact = built.report.exact;
    spdlog::info("connection {}: bake {} built {} nodes in {:.1f} ms", id_, bake_id, done.node_count, done.build_ms);
    if (recorder_.enabled()) {
        Status recorded = recorder_.record(done.result_channel, encode_result_channel(*tree));
        if (!recorded) spdlog::warn("connection {}: recording failed: {}", id_, recorded.error());
    }
    send(ProgressMsg{bake_id, "streaming", 100.0f});
    stream_.emplace(tree, next_channel_id_++, std::move(done), kDefaultChunkBytes);
    wake_writer();
}

}  // namespace lc::bake

#include "editor_client/bake/bake_client.h"

#include <chrono>
#include <sstream>

#include "editor_client/bake/client_outputs.h"
#include "editor_client/bake/client_session.h"
#include "editor_client/bake/server_process.h"
#include "protocol/asio.h"
#include "protocol/bake_limits.h"
#include "protocol/channel_recorder.h"
#include "protocol/channel_records.h"
#include "protocol/codec.h"
#include "protocol/endpoint.h"
#include "protocol/frame_decoder.h"
#include "protocol/tls_context.h"
#include "protocol/token_file.h"
#include "protocol/transport.h"

namespace lc::client {
namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

constexpr auto kShutdownLimit = 1000ms;

// "0.5", "10": seconds as the user wrote them.
std::string seconds_text(double seconds) {
    std::ostringstream text;
    text << seconds;
    return text.str();
}

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// The I/O of one bake: connects, moves frames between the socket and the
// ClientSession, applies the session's actions (ClientOutputs), and closes
// the connection on a timeout with one deadline timer (Asio's C++20 timeout
// example; Boost 1.74 has no awaitable operators).
class BakeConnection {
public:
    // `tls`: null for plain TCP; otherwise the client context, which outlives the connection.
    BakeConnection(asio::io_context& io, const BakeClientOptions& options, asio::ssl::context* tls,
                   ClientSession& session, ClientOutputs& outputs, Clock::time_point start)
        : io_(io),
          transport_(tls ? Transport::tls(tcp::socket(io), *tls) : Transport::plain(tcp::socket(io))),
          options_(options),
          session_(session),
          outputs_(outputs),
          deadline_timer_(io),
          bake_deadline_(start + seconds(options.timeout_seconds)),
          connect_deadline_(start + seconds(options.connect_timeout_seconds)) {}

    awaitable<void> run(std::string host, std::string port);
    // Sleeps until the deadline; ends the bake when it passes.
    awaitable<void> watch_deadline();
    // Looks at the cancel flag (after each message, and when the waker posts).
    void check_cancel();
    // Applies what the session asked for since the last call; false when that
    // failed, which ends the bake.
    bool apply_actions();

private:
    awaitable<Status> connect(const std::string& host, const std::string& port);
    awaitable<void> read_loop();
    // Writes what the session has to send; one writer at a time.
    awaitable<void> flush();
    void fail(const std::string& text);
    // Ends the bake with `error` and closes the socket, cancelling pending I/O.
    void abort(Error error);
    std::string hello_failure(const std::string& what) const;
    // Whichever comes first: the whole bake's, or (until HelloAck) the connection's.
    Clock::time_point deadline() const;
    bool connecting() const;
    static Clock::duration seconds(double value) {
        return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(value));
    }

    asio::io_context& io_;
    Transport transport_;
    const BakeClientOptions& options_;
    ClientSession& session_;
    ClientOutputs& outputs_;
    asio::steady_timer deadline_timer_;
    Clock::time_point bake_deadline_;
    Clock::time_point connect_deadline_;
    bool tls_handshaking_ = false;
    std::string address_;               // "HOST:PORT" for messages
    std::vector<uint8_t> first_bytes_;  // the server's first bytes, to recognise a TLS answer
    FrameDecoder decoder_;
    bool writing_ = false;
    bool cancel_seen_ = false;
};

void BakeConnection::fail(const std::string& text) {
    session_.fail(make_error(session_.stage() == ClientSession::Stage::kAwaitingHelloAck ? hello_failure(text)
                                                                                          : text));
    apply_actions();
}

void BakeConnection::abort(Error error) {
    session_.fail(std::move(error));
    apply_actions();
    transport_.close();
}

bool BakeConnection::apply_actions() {
    Status applied = outputs_.apply(session_.take_actions());
    if (applied) return true;
    session_.fail_outputs(applied.failure());
    // What failing asks for (an open dump discarded) cannot fail in turn.
    (void)outputs_.apply(session_.take_actions());
    return false;
}

void BakeConnection::check_cancel() {
    if (cancel_seen_ || !options_.cancel || !options_.cancel->load() || session_.finished()) return;
    cancel_seen_ = true;
    session_.cancel();
    apply_actions();
    // Before BakeRequest the upload owns the socket's writes: closing cancels.
    if (session_.finished()) transport_.close();
    else asio::co_spawn(io_, flush(), asio::detached);
}

awaitable<void> BakeConnection::flush() {
    if (writing_) co_return;
    writing_ = true;
    while (std::optional<Message> message = session_.next_message()) {
        // Before the message goes: a recording that fails ends the bake unsent.
        if (!apply_actions()) break;
        std::vector<uint8_t> frame = encode_frame(*message);
        boost::system::error_code ec = co_await transport_.write(asio::buffer(frame));
        if (ec) {
            fail("connection lost while sending " + std::string(message_name(*message)) + ": " + ec.message());
            break;
        }
    }
    writing_ = false;
}

bool BakeConnection::connecting() const {
    return session_.stage() == ClientSession::Stage::kConnecting ||
           session_.stage() == ClientSession::Stage::kAwaitingHelloAck;
}

Clock::time_point BakeConnection::deadline() const {
    return connecting() ? std::min(connect_deadline_, bake_deadline_) : bake_deadline_;
}

awaitable<void> BakeConnection::watch_deadline() {
    while (!session_.finished()) {
        const Clock::time_point at = deadline();
        if (Clock::now() >= at) {
            const std::string limit = seconds_text(options_.connect_timeout_seconds) + " s";
            if (at == bake_deadline_) {
                abort(make_error("bake timed out after " +
                                 std::to_string(static_cast<int>(options_.timeout_seconds)) + " s"));
            } else if (tls_handshaking_) {
                abort(make_error("TLS handshake with " + address_ + " did not finish within " + limit +
                                 " (is the server started with --tls-cert?)"));
            } else if (session_.stage() == ClientSession::Stage::kConnecting) {
                abort(make_error("cannot connect to " + address_ + " within " + limit));
            } else {
                abort(make_error("the server at " + address_ + " accepted the connection but did not answer Hello within " +
                                 limit + " (--connect-timeout)"));
            }
            co_return;
        }
        deadline_timer_.expires_at(at);
        boost::system::error_code ec;
        co_await deadline_timer_.async_wait(asio::redirect_error(asio::use_awaitable, ec));
    }
}

awaitable<Status> BakeConnection::connect(const std::string& host, const std::string& port) {
    address_ = host + ":" + port;
    boost::system::error_code ec;
    tcp::resolver resolver(io_);
    auto endpoints = co_await resolver.async_resolve(host, port, asio::redirect_error(asio::use_awaitable, ec));
    if (ec) co_return make_error("cannot resolve server '" + host + "': " + ec.message());
    co_await asio::async_connect(transport_.lowest_layer(), endpoints,
                                 asio::redirect_error(asio::use_awaitable, ec));
    if (ec) co_return make_error("cannot connect to " + address_ + ": " + ec.message());
    transport_.lowest_layer().set_option(tcp::no_delay(true), ec);
    if (!transport_.is_tls()) co_return Ok{};

    if (Status named = transport_.expect_peer_host(host); !named) co_return make_error(named.error());
    tls_handshaking_ = true;
    ec = co_await transport_.handshake(TransportRole::kClient);
    tls_handshaking_ = false;
    if (!ec) co_return Ok{};
    std::string text = "TLS handshake with " + address_ + " failed: " + transport_.handshake_error_text(ec);
    if (is_certificate_rejection(ec))
        text += "; the server's certificate must be signed by the CA given with --tls-ca FILE "
                "(or be that file) and name '" + host + "'";
    else if (!is_peer_closed(ec))
        text += " (is the server started with --tls-cert? without it, drop --tls)";
    co_return make_error(text);
}

// Why the Hello exchange failed, with the likely cause when a plain client
// meets a TLS server (which answers with a TLS record, or closes at once).
std::string BakeConnection::hello_failure(const std::string& what) const {
    if (transport_.is_tls()) return what;
    if (looks_like_tls_record(first_bytes_.data(), first_bytes_.size()))
        return "the server at " + address_ + " speaks TLS: connect with --tls (and --tls-ca FILE when its "
               "certificate is self-signed)";
    if (first_bytes_.empty())
        return what + " before answering Hello (if the server uses TLS, started with --tls-cert, "
                      "connect with --tls)";
    return what;
}

awaitable<void> BakeConnection::read_loop() {
    // The socket is read straight into the frame being decoded, and a result
    // chunk's records are read where they lie in that frame: no copy of either.
    constexpr size_t kReadBytes = 256 * 1024;
    std::vector<std::vector<uint8_t>> frames;
    while (!session_.finished()) {
        boost::system::error_code ec;
        const std::span<uint8_t> into = decoder_.read_buffer(kReadBytes);
        size_t n = co_await transport_.read_some(asio::buffer(into.data(), into.size()), ec);
        if (session_.finished()) break;
        if (ec) {
            fail(is_peer_closed(ec) ? "the server closed the connection" : "connection lost: " + ec.message());
            break;
        }
        size_t keep = std::min(n, first_bytes_.size() < 2 ? 2 - first_bytes_.size() : 0);
        first_bytes_.insert(first_bytes_.end(), into.data(), into.data() + keep);
        frames.clear();
        bool framing_ok = decoder_.commit(n, frames);
        for (auto& frame : frames) {
            Result<Message> message = decode_message_in_frame(frame);
            if (!message) {
                fail("malformed frame from the server: " + message.error());
                break;
            }
            session_.on_message(message.value());
            apply_actions();  // while the frame the message views is alive
            decoder_.recycle(std::move(frame));
            check_cancel();
            if (session_.finished()) break;
        }
        if (!framing_ok && !session_.finished()) fail("bad frame from the server: " + decoder_.error());
        co_await flush();
    }
}

awaitable<void> BakeConnection::run(std::string host, std::string port) {
    check_cancel();
    // GCC 12 destroys temporaries in co_await expressions twice: every awaited
    // call below takes named locals only.
    Status connected = co_await connect(host, port);
    if (!connected) {
        session_.fail(connected.failure());
        apply_actions();
    } else if (!session_.finished()) {
        session_.start();
        co_await flush();
        co_await read_loop();
    }
    deadline_timer_.cancel();
    // BakeDone: an orderly end (TLS close_notify); anything else: cut the connection.
    if (session_.succeeded()) co_await transport_.shutdown(kShutdownLimit);
    else transport_.close();
}

}  // namespace

Result<BakeOutcome> bake_lights(std::span<const SceneLight> lights, const Guid& scene_guid,
                                const BakeClientOptions& options) {
    for (size_t i = 0; i < lights.size(); ++i)
        if (Status valid = validate_scene_light(lights[i], i); !valid) return make_error(valid.error());

    std::unique_ptr<ServerProcess> spawned;
    std::string address = options.server;
    if (options.spawn_server && options.tls)
        return make_error("--tls is for --server: a spawned server listens on loopback without TLS");
    if (options.spawn_server) {
        auto process = ServerProcess::spawn(1, spawned_server_flags(options.ranks, options.spawned_server_args));
        if (!process) return make_error(process.error());
        spawned = std::move(process.value());
        address = spawned->address();
    }
    Result<Endpoint> endpoint = parse_endpoint(address);
    if (!endpoint) return make_error("server " + endpoint.error());
    const std::string host = endpoint.value().host;
    const std::string port = std::to_string(endpoint.value().port);
    Result<std::string> token = options.token_file.empty() ? Result<std::string>(std::string())
                                                           : read_token_file(options.token_file);
    if (!token) return make_error(token.error());
    std::shared_ptr<asio::ssl::context> tls;
    if (options.tls) {
        auto context = make_tls_client_context(options.tls_ca_file);
        if (!context) return make_error(context.error());
        tls = std::move(context.value());
    }

    std::vector<SceneLight> tree_lights;
    tree_lights.reserve(lights.size());
    for (const SceneLight& light : lights)
        if (!light.classic) tree_lights.push_back(light);
    ChannelRecorder recorder(options.record_dir);
    ClientSessionOptions session_options;
    session_options.token = token.value();
    session_options.request = BakeRequestMsg{.bake_id = 1,
                                             .builder = options.builder,
                                             .seed = options.seed,
                                             .representative_rule = options.representative_rule,
                                             .pairing = options.pairing,
                                             .exact_pairing_limit = options.exact_pairing_limit,
                                             .environment_lights = options.environment_lights,
                                             // Only a bake with geometry has area lights to sample.
                                             .area_lights = options.geometry ? options.area_lights : 0u,
                                             .indirect = options.indirect,
                                             .ranks = options.ranks};
    // The server checks the same limits on arrival; checked here, nothing is sent for a request it would
    // refuse.
    if (Status settings = validate_bake_settings(session_options.request); !settings)
        return make_error("bake settings refused before sending: " + settings.error());
    session_options.environment = options.environment;
    session_options.geometry = options.geometry;
    session_options.record_channels = recorder.enabled();
    session_options.keep_result_channel = options.keep_result_channel;
    session_options.decode_tree = options.decode_tree;
    session_options.write_dump = !options.result_dump.empty();
    ClientSession session(std::move(tree_lights), scene_guid, std::move(session_options));
    ClientOutputs outputs({.result_dump = options.result_dump,
                           .recorder = &recorder,
                           .on_progress = options.on_progress,
                           .on_warning = options.on_warning});

    auto start = Clock::now();
    asio::io_context io;
    BakeConnection connection(io, options, tls.get(), session, outputs, start);
    if (options.waker) options.waker->attach([&] { asio::post(io, [&] { connection.check_cancel(); }); });
    asio::co_spawn(io, connection.run(host, port), [&](std::exception_ptr error) {
        if (error) session.fail(make_error("internal error in the bake client"));
    });
    asio::co_spawn(io, connection.watch_deadline(), asio::detached);
    io.run();
    if (options.waker) options.waker->detach();
    if (!session.finished()) return make_error("bake client stopped without a result");
    (void)outputs.apply(session.take_actions());  // an internal error's discarded dump
    Result<BakeOutcome> outcome = session.take_result();
    if (outcome) {
        outcome->total_ms = ms_since(start);
        outcome->write_ms = outputs.commit_ms();
    }
    return outcome;
}

void BakeWaker::wake() {
    std::lock_guard lock(mutex_);
    if (wake_) wake_();
}

void BakeWaker::attach(std::function<void()> wake) {
    std::lock_guard lock(mutex_);
    wake_ = std::move(wake);
}

void BakeWaker::detach() {
    std::lock_guard lock(mutex_);
    wake_ = nullptr;
}

}  // namespace lc::client

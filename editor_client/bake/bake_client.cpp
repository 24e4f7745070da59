#include "editor_client/bake/bake_client.h"

#include <chrono>
#include <deque>

#include "editor_client/bake/server_process.h"
#include "protocol/asio.h"
#include "protocol/channel_name.h"
#include "protocol/channel_recorder.h"
#include "protocol/channel_records.h"
#include "protocol/codec.h"
#include "protocol/frame_decoder.h"
#include "protocol/tls_context.h"
#include "protocol/transport.h"

namespace lc::client {
namespace {

using Clock = std::chrono::steady_clock;
using namespace std::chrono_literals;

// A server that never answers the TLS handshake (one that does not speak TLS
// and waits for more bytes) is given up on after this long.
constexpr auto kTlsHandshakeLimit = 10s;
constexpr auto kShutdownLimit = 1000ms;

double ms_since(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

bool split_host_port(const std::string& text, std::string& host, std::string& port) {
    size_t colon = text.rfind(':');
    if (colon == std::string::npos || colon == 0 || colon + 1 == text.size()) return false;
    host = text.substr(0, colon);
    port = text.substr(colon + 1);
    if (host.size() > 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
    return port.find_first_not_of("0123456789") == std::string::npos;
}

Result<std::string> read_token(const std::filesystem::path& path) {
    if (path.empty()) return std::string();
    std::FILE* f = std::fopen(path.c_str(), "r");
    if (!f) return make_error("cannot read token file '" + path.string() + "'");
    char buffer[1024] = {};
    size_t n = std::fread(buffer, 1, sizeof buffer - 1, f);
    std::fclose(f);
    std::string token(buffer, n);
    token = token.substr(0, token.find_first_of("\r\n"));
    while (!token.empty() && (token.back() == ' ' || token.back() == '\t')) token.pop_back();
    if (token.empty()) return make_error("token file '" + path.string() + "' is empty");
    return token;
}

// One bake over one connection, as a coroutine on a private io_context.
class BakeSession {
public:
    // `tls`: null for plain TCP; otherwise the client context, which outlives the session.
    BakeSession(asio::io_context& io, const BakeClientOptions& options, asio::ssl::context* tls)
        : io_(io),
          transport_(tls ? Transport::tls(tcp::socket(io), *tls) : Transport::plain(tcp::socket(io))),
          options_(options) {}

    awaitable<Result<BakeOutcome>> run(std::span<const SceneLight> lights, const Guid& scene_guid,
                                      std::string host, std::string port, std::string token);
    awaitable<void> watchdog(Clock::time_point deadline);

    bool finished = false;
    std::string abort_reason;

private:
    awaitable<Status> connect(const std::string& host, const std::string& port);
    awaitable<Status> send(const Message& message);
    awaitable<Result<Message>> receive();
    std::string hello_failure(const std::string& what) const;
    void abort(const std::string& reason) {
        if (abort_reason.empty()) abort_reason = reason;
        transport_.close();
    }
    Error failure(const std::string& what) {
        return make_error(abort_reason.empty() ? what : abort_reason);
    }

    asio::io_context& io_;
    Transport transport_;
    const BakeClientOptions& options_;
    std::string address_;  // "HOST:PORT" for messages
    std::optional<Clock::time_point> handshake_deadline_;  // set while a TLS handshake runs
    std::vector<uint8_t> first_bytes_;  // the server's first bytes, to recognise a TLS answer
    FrameDecoder decoder_;
    std::deque<std::vector<uint8_t>> frames_;
    bool uploading_ = true;
    bool cancel_sent_ = false;
    uint32_t bake_id_ = 1;
};

awaitable<Status> BakeSession::send(const Message& message) {
    std::vector<uint8_t> frame = encode_frame(message);
    boost::system::error_code ec = co_await transport_.write(asio::buffer(frame));
    if (ec) co_return failure("connection lost while sending " + std::string(message_name(message)) + ": " + ec.message());
    co_return Ok{};
}

awaitable<Result<Message>> BakeSession::receive() {
    std::vector<uint8_t> buffer(256 * 1024);
    std::vector<std::vector<uint8_t>> decoded;
    while (frames_.empty()) {
        boost::system::error_code ec;
        size_t n = co_await transport_.read_some(asio::buffer(buffer), ec);
        if (ec)
            co_return failure(is_peer_closed(ec) ? "the server closed the connection"
                                                 : "connection lost: " + ec.message());
        size_t keep = std::min(n, first_bytes_.size() < 2 ? 2 - first_bytes_.size() : 0);
        first_bytes_.insert(first_bytes_.end(), buffer.data(), buffer.data() + keep);
        decoded.clear();
        bool ok = decoder_.consume({buffer.data(), n}, decoded);
        for (auto& f : decoded) frames_.push_back(std::move(f));
        if (!ok && frames_.empty()) co_return failure("bad frame from the server: " + decoder_.error());
    }
    std::vector<uint8_t> frame = std::move(frames_.front());
    frames_.pop_front();
    Result<Message> message = decode_message(frame);
    if (!message) co_return failure("malformed frame from the server: " + message.error());
    co_return message;
}

awaitable<void> BakeSession::watchdog(Clock::time_point deadline) {
    asio::steady_timer timer(io_);
    while (!finished) {
        boost::system::error_code ec;
        timer.expires_after(50ms);
        co_await timer.async_wait(asio::redirect_error(asio::use_awaitable, ec));
        if (finished) co_return;
        if (handshake_deadline_ && Clock::now() > *handshake_deadline_) {
            auto limit_s = std::chrono::duration_cast<std::chrono::seconds>(kTlsHandshakeLimit).count();
            abort("TLS handshake with " + address_ + " did not finish within " + std::to_string(limit_s) +
                  " s (is the server started with --tls-cert?)");
            co_return;
        }
        if (Clock::now() > deadline) {
            abort("bake timed out after " + std::to_string(static_cast<int>(options_.timeout_seconds)) + " s");
            co_return;
        }
        if (options_.cancel && options_.cancel->load() && !cancel_sent_) {
            cancel_sent_ = true;
            if (uploading_) {  // the upload coroutine owns the socket's writes: closing cancels
                abort("bake cancelled");
                co_return;
            }
            std::vector<uint8_t> frame = encode_frame(CancelMsg{bake_id_});
            ec = co_await transport_.write(asio::buffer(frame));
        }
    }
}

awaitable<Status> BakeSession::connect(const std::string& host, const std::string& port) {
    address_ = host + ":" + port;
    boost::system::error_code ec;
    tcp::resolver resolver(io_);
    auto endpoints = co_await resolver.async_resolve(host, port, asio::redirect_error(asio::use_awaitable, ec));
    if (ec) co_return failure("cannot resolve server '" + host + "': " + ec.message());
    co_await asio::async_connect(transport_.lowest_layer(), endpoints,
                                 asio::redirect_error(asio::use_awaitable, ec));
    if (ec) co_return failure("cannot connect to " + address_ + ": " + ec.message());
    transport_.lowest_layer().set_option(tcp::no_delay(true), ec);
    if (!transport_.is_tls()) co_return Ok{};

    if (Status named = transport_.expect_peer_host(host); !named) co_return make_error(named.error());
    handshake_deadline_ = Clock::now() + kTlsHandshakeLimit;
    ec = co_await transport_.handshake(TransportRole::kClient);
    handshake_deadline_.reset();
    if (!abort_reason.empty()) co_return make_error(abort_reason);  // timed out or cancelled
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
std::string BakeSession::hello_failure(const std::string& what) const {
    if (transport_.is_tls()) return what;
    if (looks_like_tls_record(first_bytes_.data(), first_bytes_.size()))
        return "the server at " + address_ + " speaks TLS: connect with --tls (and --tls-ca FILE when its "
               "certificate is self-signed)";
    if (first_bytes_.empty())
        return what + " before answering Hello (if the server uses TLS, started with --tls-cert, "
                      "connect with --tls)";
    return what;
}

awaitable<Result<BakeOutcome>> BakeSession::run(std::span<const SceneLight> lights, const Guid& scene_guid,
                                                std::string host, std::string port, std::string token) {
    auto start = Clock::now();
    ChannelRecorder recorder(options_.record_dir);
    // GCC 12 destroys temporaries in co_await expressions twice: every awaited
    // call below takes named locals only.
    Status connected = co_await connect(host, port);
    if (!connected) co_return make_error(connected.error());

    // Protocol handshake.
    Message hello = HelloMsg{kProtocolVersion, "editor_client 0.1.0", token};
    Status sent = co_await send(hello);
    if (!sent) co_return make_error(hello_failure(sent.error()));
    {
        Result<Message> reply = co_await receive();
        if (!reply) co_return make_error(hello_failure(reply.error()));
        if (auto* err = std::get_if<ErrorMsg>(&reply.value())) co_return make_error("server refused the connection: " + err->text);
        auto* ack = std::get_if<HelloAckMsg>(&reply.value());
        if (!ack) co_return make_error(std::string("expected HelloAck, got ") + message_name(reply.value()));
        if (ack->protocol_version != kProtocolVersion)
            co_return make_error("protocol version mismatch: server speaks " + ack->protocol_version.to_hex() +
                                 ", client speaks " + kProtocolVersion.to_hex());
    }

    // Scene channel: the tree lights, count-prefixed, in bounded chunks.
    std::vector<SceneLight> tree_lights;
    tree_lights.reserve(lights.size());
    for (const SceneLight& l : lights)
        if (!l.classic) tree_lights.push_back(l);
    std::vector<uint8_t> scene_bytes = encode_scene_channel(tree_lights);
    std::string scene_channel = scene_channel_name(scene_guid);
    const uint32_t channel_id = 1;
    auto upload_start = Clock::now();
    Message open = OpenChannelMsg{channel_id, scene_channel, scene_bytes.size()};
    sent = co_await send(open);
    if (!sent) co_return make_error(sent.error());
    for (size_t offset = 0; offset < scene_bytes.size(); offset += kDefaultChunkBytes) {
        size_t n = std::min(kDefaultChunkBytes, scene_bytes.size() - offset);
        Message write = WriteChannelMsg{channel_id, offset, {scene_bytes.begin() + offset, scene_bytes.begin() + offset + n}};
        sent = co_await send(write);
        if (!sent) co_return make_error(sent.error());
    }
    Message close_channel = CloseChannelMsg{channel_id};
    sent = co_await send(close_channel);
    if (!sent) co_return make_error(sent.error());
    if (recorder.enabled()) {
        if (Status r = recorder.record(scene_channel, scene_bytes); !r) co_return make_error(r.error());
    }
    scene_bytes = {};

    BakeRequestMsg request;
    request.bake_id = bake_id_;
    request.scene_channel = scene_channel;
    request.builder = options_.builder;
    request.seed = options_.seed;
    request.representative_rule = options_.representative_rule;
    request.pairing = options_.pairing;
    request.exact_pairing_limit = options_.exact_pairing_limit;
    Message request_message = request;
    sent = co_await send(request_message);
    if (!sent) co_return make_error(sent.error());
    uploading_ = false;
    double upload_ms = ms_since(upload_start);

    // Progress, warnings, then the result channel and BakeDone.
    BakeOutcome outcome;
    outcome.upload_ms = upload_ms;
    ResultChannelReader reader;
    std::vector<uint8_t> result_bytes;
    std::optional<uint32_t> result_channel_id;
    uint64_t expected_bytes = 0;
    bool channel_closed = false;
    Clock::time_point download_start;
    while (true) {
        Result<Message> message = co_await receive();
        if (!message) co_return make_error(message.error());
        Message& m = message.value();
        if (auto* p = std::get_if<ProgressMsg>(&m)) {
            if (options_.on_progress) options_.on_progress(*p);
        } else if (auto* w = std::get_if<WarningMsg>(&m)) {
            outcome.warnings.push_back(w->text);
            if (options_.on_warning) options_.on_warning(w->text);
        } else if (auto* e = std::get_if<ErrorMsg>(&m)) {
            co_return make_error(e->code == ErrorCode::kCancelled ? "bake cancelled" : "server: " + e->text);
        } else if (auto* open = std::get_if<OpenChannelMsg>(&m)) {
            auto name = ChannelName::parse(open->name);
            if (!name || name->version != kLightcutsVersionGuid || name->extension != kLightcutsExtension)
                co_return make_error("server opened an unexpected channel '" + open->name + "' (expected version " +
                                     kLightcutsVersionGuid.to_hex() + ", extension ." + kLightcutsExtension + ")");
            if (result_channel_id) co_return make_error("server opened a second result channel");
            result_channel_id = open->channel_id;
            outcome.result_channel_name = open->name;
            expected_bytes = open->total_bytes;
            download_start = Clock::now();
        } else if (auto* write = std::get_if<WriteChannelMsg>(&m)) {
            if (!result_channel_id || write->channel_id != *result_channel_id)
                co_return make_error("server wrote to channel " + std::to_string(write->channel_id) + " which is not open");
            if (write->offset != result_bytes.size() || result_bytes.size() + write->data.size() > expected_bytes)
                co_return make_error("result channel out of order or longer than announced");
            if (Status s = reader.consume(write->data); !s) co_return make_error("result channel: " + s.error());
            result_bytes.insert(result_bytes.end(), write->data.begin(), write->data.end());
            if (options_.on_progress && reader.nodes_expected() > 0) {
                float pct = 100.0f * static_cast<float>(reader.nodes_received()) / static_cast<float>(reader.nodes_expected());
                options_.on_progress(ProgressMsg{bake_id_, "receiving", pct});
            }
        } else if (auto* close = std::get_if<CloseChannelMsg>(&m)) {
            if (!result_channel_id || close->channel_id != *result_channel_id)
                co_return make_error("server closed a channel that is not open");
            channel_closed = true;
        } else if (auto* done = std::get_if<BakeDoneMsg>(&m)) {
            if (!channel_closed) co_return make_error("BakeDone arrived before the result channel was closed");
            Result<LightTree> tree = reader.finish();
            if (!tree) co_return make_error("result channel: " + tree.error());
            if (tree->nodes.size() != done->node_count)
                co_return make_error("BakeDone announces " + std::to_string(done->node_count) + " nodes, channel held " +
                                     std::to_string(tree->nodes.size()));
            outcome.tree = std::move(tree.value());
            outcome.done = *done;
            outcome.download_ms = ms_since(download_start);
            if (recorder.enabled()) {
                if (Status r = recorder.record(outcome.result_channel_name, result_bytes); !r) co_return make_error(r.error());
            }
            outcome.result_channel = std::move(result_bytes);
            outcome.total_ms = ms_since(start);
            co_await transport_.shutdown(kShutdownLimit);
            co_return outcome;
        } else {
            co_return make_error(std::string("unexpected message from the server: ") + message_name(m));
        }
    }
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
        auto process = ServerProcess::spawn();
        if (!process) return make_error(process.error());
        spawned = std::move(process.value());
        address = spawned->address();
    }
    std::string host, port;
    if (!split_host_port(address, host, port)) return make_error("server address must be HOST:PORT, got '" + address + "'");
    Result<std::string> token = read_token(options.token_file);
    if (!token) return make_error(token.error());
    std::shared_ptr<asio::ssl::context> tls;
    if (options.tls) {
        auto context = make_tls_client_context(options.tls_ca_file);
        if (!context) return make_error(context.error());
        tls = std::move(context.value());
    }

    asio::io_context io;
    BakeSession session(io, options, tls.get());
    std::optional<Result<BakeOutcome>> outcome;
    auto deadline = Clock::now() + std::chrono::milliseconds(static_cast<int64_t>(options.timeout_seconds * 1000.0));
    asio::co_spawn(io, session.run(lights, scene_guid, host, port, token.value()),
                   [&](std::exception_ptr error, Result<BakeOutcome> result) {
                       session.finished = true;
                       if (error) outcome.emplace(make_error("internal error in the bake client"));
                       else outcome.emplace(std::move(result));
                   });
    asio::co_spawn(io, session.watchdog(deadline), asio::detached);
    io.run();
    if (!outcome) return make_error("bake client stopped without a result");
    return std::move(*outcome);
}

}  // namespace lc::client

#include "editor_client/bake/server_status.h"

#include <chrono>
#include <memory>
#include <optional>
#include <vector>

#include "lightcuts/version.h"
#include "protocol/asio.h"
#include "protocol/codec.h"
#include "protocol/endpoint.h"
#include "protocol/frame_decoder.h"
#include "protocol/tls_context.h"
#include "protocol/token_file.h"
#include "protocol/transport.h"

namespace lc::client {
namespace {

constexpr auto kShutdownLimit = std::chrono::milliseconds(500);

// One request and its answer over a connected transport. GCC 12 destroys
// temporaries in co_await expressions twice: every awaited call takes named locals.
class StatusExchange {
public:
    explicit StatusExchange(Transport& transport) : transport_(transport) {}

    awaitable<Status> send(const Message& message) {
        const std::vector<uint8_t> frame = encode_frame(message);
        const asio::const_buffer bytes = asio::buffer(frame);
        const boost::system::error_code ec = co_await transport_.write(bytes);
        if (ec) co_return make_error("connection lost while sending " + std::string(message_name(message)));
        co_return Ok{};
    }

    // The next message; the server's ErrorMessage becomes the error, in its words.
    awaitable<Result<Message>> receive() {
        std::vector<uint8_t> buffer(64 * 1024);
        while (frames_.empty()) {
            boost::system::error_code ec;
            const asio::mutable_buffer into = asio::buffer(buffer);
            const size_t n = co_await transport_.read_some(into, ec);
            if (ec) co_return make_error(is_peer_closed(ec) ? "the server closed the connection" : "connection lost");
            if (!decoder_.consume({buffer.data(), n}, frames_))
                co_return make_error("bad frame from the server: " + decoder_.error());
        }
        const std::vector<uint8_t> frame = std::move(frames_.front());
        frames_.erase(frames_.begin());
        Result<Message> message = decode_message(frame);
        if (!message) co_return make_error("malformed frame from the server: " + message.error());
        if (const auto* error = std::get_if<ErrorMsg>(&*message)) co_return make_error("the server refused: " + error->text);
        co_return message;
    }

private:
    Transport& transport_;
    FrameDecoder decoder_;
    std::vector<std::vector<uint8_t>> frames_;
};

awaitable<Status> connect(Transport& transport, const std::string& host, const std::string& port) {
    boost::system::error_code ec;
    // A numeric address needs no resolver: asio's runs on a thread of its own, which
    // took 3 to 60 ms to start on a loaded machine (docs/bench/ops2.md).
    const asio::ip::address numeric = asio::ip::make_address(host, ec);
    if (!ec) {
        co_await transport.lowest_layer().async_connect(tcp::endpoint(numeric, uint16_t(std::stoi(port))),
                                                        asio::redirect_error(asio::use_awaitable, ec));
    } else {
        ec.clear();
        tcp::resolver resolver(transport.get_executor());
        auto endpoints =
            co_await resolver.async_resolve(host, port, asio::redirect_error(asio::use_awaitable, ec));
        if (ec) co_return make_error("cannot resolve server '" + host + "': " + ec.message());
        co_await asio::async_connect(transport.lowest_layer(), endpoints,
                                     asio::redirect_error(asio::use_awaitable, ec));
    }
    if (ec) co_return make_error("cannot connect to " + host + ":" + port + ": " + ec.message());
    if (!transport.is_tls()) co_return Ok{};
    if (Status named = transport.expect_peer_host(host); !named) co_return make_error(named.error());
    ec = co_await transport.handshake(TransportRole::kClient);
    if (ec) co_return make_error("TLS handshake with " + host + ":" + port + " failed: " + transport.handshake_error_text(ec));
    co_return Ok{};
}

// Milliseconds since `since`, and `since` moved to now.
double lap_ms(std::chrono::steady_clock::time_point& since) {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - since).count();
    since = now;
    return ms;
}

awaitable<Result<StatusReplyMsg>> ask(Transport& transport, std::string host, std::string port, std::string token,
                                      ServerStatusTiming* timing) {
    ServerStatusTiming ignored;
    if (!timing) timing = &ignored;
    auto since = std::chrono::steady_clock::now();
    Status connected = co_await connect(transport, host, port);
    if (!connected) co_return connected.failure();
    timing->connect_ms = lap_ms(since);
    StatusExchange exchange(transport);
    const Message hello = HelloMsg{kProtocolVersion, std::string("editor_client ") + kVersion, token};
    Status sent = co_await exchange.send(hello);
    if (!sent) co_return sent.failure();
    Result<Message> ack = co_await exchange.receive();
    if (!ack) co_return ack.failure();
    if (!std::holds_alternative<HelloAckMsg>(*ack))
        co_return make_error(std::string("expected HelloAck, the server sent ") + message_name(*ack));
    timing->hello_ms = lap_ms(since);
    const Message request = StatusRequestMsg{1};
    sent = co_await exchange.send(request);
    if (!sent) co_return sent.failure();
    Result<Message> reply = co_await exchange.receive();
    if (!reply) co_return reply.failure();
    auto* status = std::get_if<StatusReplyMsg>(&*reply);
    if (!status) co_return make_error(std::string("expected StatusReply, the server sent ") + message_name(*reply));
    timing->status_ms = lap_ms(since);
    StatusReplyMsg answer = std::move(*status);
    co_await transport.shutdown(kShutdownLimit);
    co_return answer;
}

}  // namespace

Result<StatusReplyMsg> query_server_status(const ServerStatusQuery& query) {
    Result<Endpoint> endpoint = parse_endpoint(query.server);
    if (!endpoint) return make_error("server " + endpoint.error());
    const std::string host = endpoint->host;
    const std::string port = std::to_string(endpoint->port);
    Result<std::string> token =
        query.token_file.empty() ? Result<std::string>(std::string()) : read_token_file(query.token_file);
    if (!token) return token.failure();
    std::shared_ptr<asio::ssl::context> tls;
    if (query.tls) {
        auto context = make_tls_client_context(query.tls_ca_file);
        if (!context) return context.failure();
        tls = std::move(context.value());
    }
    asio::io_context io;
    Transport transport = tls ? Transport::tls(tcp::socket(io), *tls) : Transport::plain(tcp::socket(io));
    std::optional<Result<StatusReplyMsg>> outcome;
    asio::steady_timer deadline(io);
    deadline.expires_after(std::chrono::duration_cast<std::chrono::steady_clock::duration>(
        std::chrono::duration<double>(query.timeout_seconds)));
    deadline.async_wait([&](const boost::system::error_code& ec) {
        if (!ec && !outcome) transport.close();
    });
    asio::co_spawn(io, ask(transport, host, port, *token, query.timing), [&](std::exception_ptr error, Result<StatusReplyMsg> result) {
        deadline.cancel();
        outcome = error ? Result<StatusReplyMsg>(make_error("server-status failed")) : std::move(result);
    });
    io.run();
    if (!outcome) return make_error("no answer from " + query.server);
    if (!*outcome && deadline.expiry() <= std::chrono::steady_clock::now())
        return make_error("no status from " + query.server + " within " + std::to_string(query.timeout_seconds) + " s");
    return std::move(*outcome);
}

}  // namespace lc::client

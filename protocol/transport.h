#pragma once
// The byte stream under the channel protocol: plain TCP, or TLS over TCP
// (Boost.Asio's OpenSSL stream). The server's connections and the bake client
// read, write, handshake and close through this one interface, so the framing
// and message code is the same whether the channel is encrypted or not.
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>

#include "protocol/asio.h"
#include "lightcuts/result.h"

// After protocol/asio.h, which puts <utility> first as Boost 1.74 needs.
#include <boost/asio/ssl.hpp>

namespace lc {

using TlsStream = asio::ssl::stream<tcp::socket>;

enum class TransportRole { kClient, kServer };

class Transport {
public:
    static Transport plain(tcp::socket socket);
    // `context` must outlive the transport (the server and the bake client own theirs).
    static Transport tls(tcp::socket socket, asio::ssl::context& context);

    Transport(Transport&&) = default;
    Transport(const Transport&) = delete;
    Transport& operator=(const Transport&) = delete;
    Transport& operator=(Transport&&) = delete;  // asio's ssl::stream cannot be move-assigned

    bool is_tls() const { return std::holds_alternative<TlsStream>(stream_); }
    // The TCP socket under any TLS layer: for connect, options and endpoints.
    tcp::socket& lowest_layer();
    tcp::socket::executor_type get_executor() { return lowest_layer().get_executor(); }

    // TLS client, before the handshake: `host` is sent as SNI (unless it is an
    // IP literal, which SNI does not carry) and the server's certificate must
    // name it (DNS name, or IP address for a literal). Plain: nothing to do.
    Status expect_peer_host(const std::string& host);

    // Plain: completes at once. TLS: the handshake, certificate checks included.
    awaitable<boost::system::error_code> handshake(TransportRole role);
    awaitable<size_t> read_some(asio::mutable_buffer buffer, boost::system::error_code& ec);
    // Writes all of `buffer`.
    awaitable<boost::system::error_code> write(asio::const_buffer buffer);
    // An orderly end: TLS sends close_notify and waits up to `limit` for the
    // peer's; then the socket is shut down and closed. Errors are of no use here.
    awaitable<void> shutdown(std::chrono::milliseconds limit);
    // Closes at once, cancelling pending operations: for aborts and deadline timers.
    void close();

    // The reason a handshake failed, with the certificate verification result
    // when that is what failed: "certificate verify failed (self-signed certificate)".
    std::string handshake_error_text(const boost::system::error_code& ec);

private:
    explicit Transport(tcp::socket socket) : stream_(std::move(socket)) {}
    Transport(tcp::socket socket, asio::ssl::context& context)
        : stream_(std::in_place_type<TlsStream>, std::move(socket), context) {}

    std::variant<tcp::socket, TlsStream> stream_;
};

// True when `ec` means the peer ended the stream: EOF, or a TLS peer that
// closed its socket without close_notify (which most peers do when done).
bool is_peer_closed(const boost::system::error_code& ec);

// True when a handshake failed because the peer's certificate did not verify
// (untrusted, expired, or not naming the host).
bool is_certificate_rejection(const boost::system::error_code& ec);

// True when `bytes` begin like a TLS record (content type 20..23, major version
// 3): a plain peer reading them was answered by a TLS server.
bool looks_like_tls_record(const uint8_t* bytes, size_t size);

}  // namespace lc

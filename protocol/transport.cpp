#include "protocol/transport.h"

#include <openssl/err.h>
#include <openssl/ssl.h>
#include <openssl/x509.h>
#include <openssl/x509_vfy.h>

#include <memory>

namespace lc {
namespace {

auto ec_token(boost::system::error_code& ec) {
    return asio::redirect_error(asio::use_awaitable, ec);
}

}  // namespace

Transport Transport::plain(tcp::socket socket) {
    return Transport(std::move(socket));
}

Transport Transport::tls(tcp::socket socket, asio::ssl::context& context) {
    return Transport(std::move(socket), context);
}

tcp::socket& Transport::lowest_layer() {
    if (auto* tls = std::get_if<TlsStream>(&stream_)) return tls->next_layer();
    return std::get<tcp::socket>(stream_);
}

Status Transport::expect_peer_host(const std::string& host) {
    auto* tls = std::get_if<TlsStream>(&stream_);
    if (!tls) return Ok{};
    SSL* ssl = tls->native_handle();
    boost::system::error_code parse_error;
    asio::ip::make_address(host, parse_error);
    const bool ip_literal = !parse_error;
    // OpenSSL checks the name during chain verification, so a mismatch reports
    // as "hostname mismatch" / "IP address mismatch" in the verify result.
    X509_VERIFY_PARAM* param = SSL_get0_param(ssl);
    if (ip_literal) {
        if (X509_VERIFY_PARAM_set1_ip_asc(param, host.c_str()) != 1)
            return make_error("cannot check the server certificate against IP address '" + host + "'");
        return Ok{};
    }
    X509_VERIFY_PARAM_set_hostflags(param, X509_CHECK_FLAG_NO_PARTIAL_WILDCARDS);
    if (SSL_set1_host(ssl, host.c_str()) != 1)
        return make_error("cannot check the server certificate against host name '" + host + "'");
    if (SSL_set_tlsext_host_name(ssl, host.c_str()) != 1)
        return make_error("cannot send '" + host + "' as the TLS server name (SNI)");
    return Ok{};
}

awaitable<boost::system::error_code> Transport::handshake(TransportRole role) {
    boost::system::error_code ec;
    if (auto* tls = std::get_if<TlsStream>(&stream_)) {
        auto type =
            role == TransportRole::kClient ? asio::ssl::stream_base::client : asio::ssl::stream_base::server;
        co_await tls->async_handshake(type, ec_token(ec));
    }
    co_return ec;
}

awaitable<size_t> Transport::read_some(asio::mutable_buffer buffer, boost::system::error_code& ec) {
    if (auto* tls = std::get_if<TlsStream>(&stream_)) {
        size_t n = co_await tls->async_read_some(buffer, ec_token(ec));
        co_return n;
    }
    size_t n = co_await std::get<tcp::socket>(stream_).async_read_some(buffer, ec_token(ec));
    co_return n;
}

awaitable<boost::system::error_code> Transport::write(asio::const_buffer buffer) {
    boost::system::error_code ec;
    if (auto* tls = std::get_if<TlsStream>(&stream_))
        co_await asio::async_write(*tls, buffer, ec_token(ec));
    else
        co_await asio::async_write(std::get<tcp::socket>(stream_), buffer, ec_token(ec));
    co_return ec;
}

awaitable<void> Transport::shutdown(std::chrono::milliseconds limit) {
    if (auto* tls = std::get_if<TlsStream>(&stream_); tls && lowest_layer().is_open()) {
        // A peer that neither answers close_notify nor closes must not hold us:
        // the timer closes the socket, which ends the pending shutdown. `done`
        // keeps a late timer handler from touching this transport.
        auto done = std::make_shared<bool>(false);
        asio::steady_timer timer(get_executor());
        timer.expires_after(limit);
        timer.async_wait([this, done](const boost::system::error_code& ec) {
            if (!ec && !*done) close();
        });
        boost::system::error_code ec;
        co_await tls->async_shutdown(ec_token(ec));
        *done = true;
        timer.cancel();
    }
    close();
}

void Transport::close() {
    tcp::socket& socket = lowest_layer();
    if (!socket.is_open()) return;
    boost::system::error_code ignored;
    socket.shutdown(tcp::socket::shutdown_both, ignored);
    socket.close(ignored);
}

std::string Transport::handshake_error_text(const boost::system::error_code& ec) {
    std::string text = ec.message();
    auto* tls = std::get_if<TlsStream>(&stream_);
    if (!tls || ec.category() != asio::error::get_ssl_category()) return text;
    long verify = SSL_get_verify_result(tls->native_handle());
    if (verify != X509_V_OK) text += std::string(" (") + X509_verify_cert_error_string(verify) + ")";
    return text;
}

bool is_peer_closed(const boost::system::error_code& ec) {
    return ec == asio::error::eof || ec == asio::ssl::error::stream_truncated;
}

bool is_certificate_rejection(const boost::system::error_code& ec) {
    return ec.category() == asio::error::get_ssl_category() &&
           ERR_GET_REASON(static_cast<unsigned long>(ec.value())) == SSL_R_CERTIFICATE_VERIFY_FAILED;
}

bool looks_like_tls_record(const uint8_t* bytes, size_t size) {
    return size >= 2 && bytes[0] >= 20 && bytes[0] <= 23 && bytes[1] == 3;
}

}  // namespace lc

#include "protocol/tls_context.h"

#include <openssl/ssl.h>

#include <fstream>

namespace lc {
namespace {

constexpr long kContextOptions = asio::ssl::context::default_workarounds | asio::ssl::context::no_sslv2 |
                                 asio::ssl::context::no_sslv3 | asio::ssl::context::no_tlsv1 |
                                 asio::ssl::context::no_tlsv1_1 | asio::ssl::context::single_dh_use;

// OpenSSL's "no such file" says neither which file nor what it was for.
Status check_readable(const std::filesystem::path& path, const std::string& what) {
    std::ifstream in(path);
    if (!in) return make_error("cannot read " + what + " '" + path.string() + "'");
    return Ok{};
}

}  // namespace

Result<std::shared_ptr<asio::ssl::context>> make_tls_server_context(
    const std::filesystem::path& certificate, const std::filesystem::path& private_key) {
    if (Status readable = check_readable(certificate, "TLS certificate"); !readable)
        return make_error(readable.error());
    if (Status readable = check_readable(private_key, "TLS private key"); !readable)
        return make_error(readable.error());
    auto context = std::make_shared<asio::ssl::context>(asio::ssl::context::tls_server);
    boost::system::error_code ec;
    context->set_options(kContextOptions, ec);
    if (ec) return make_error("cannot configure TLS: " + ec.message());
    context->use_certificate_chain_file(certificate.string(), ec);
    if (ec)
        return make_error("cannot load TLS certificate '" + certificate.string() +
                          "' (PEM expected): " + ec.message());
    context->use_private_key_file(private_key.string(), asio::ssl::context::pem, ec);
    if (ec)
        return make_error("cannot load TLS private key '" + private_key.string() +
                          "' (PEM expected): " + ec.message());
    if (SSL_CTX_check_private_key(context->native_handle()) != 1)
        return make_error("TLS private key '" + private_key.string() + "' does not match certificate '" +
                          certificate.string() + "'");
    return context;
}

Result<std::shared_ptr<asio::ssl::context>> make_tls_client_context(const std::filesystem::path& ca_file) {
    auto context = std::make_shared<asio::ssl::context>(asio::ssl::context::tls_client);
    boost::system::error_code ec;
    context->set_options(kContextOptions, ec);
    if (ec) return make_error("cannot configure TLS: " + ec.message());
    if (ca_file.empty()) {
        context->set_default_verify_paths(ec);
        if (ec) return make_error("cannot load the system's trusted TLS certificates: " + ec.message());
    } else {
        if (Status readable = check_readable(ca_file, "TLS CA file"); !readable)
            return make_error(readable.error());
        context->load_verify_file(ca_file.string(), ec);
        if (ec)
            return make_error("cannot load TLS CA file '" + ca_file.string() +
                              "' (PEM expected): " + ec.message());
    }
    context->set_verify_mode(asio::ssl::verify_peer, ec);
    if (ec) return make_error("cannot configure TLS verification: " + ec.message());
    return context;
}

}  // namespace lc

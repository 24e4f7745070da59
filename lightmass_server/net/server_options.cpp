#include "lightmass_server/net/server_options.h"

#include "protocol/asio.h"

namespace lc::bake {

bool is_loopback_host(const std::string& host) {
    if (host == "localhost") return true;
    boost::system::error_code ec;
    auto address = asio::ip::make_address(host, ec);
    return !ec && address.is_loopback();
}

Status check_server_security(const ServerOptions& options) {
    const bool has_cert = !options.tls_certificate.empty();
    const bool has_key = !options.tls_private_key.empty();
    if (has_cert != has_key)
        return make_error(has_cert ? "--tls-cert needs --tls-key FILE (the certificate's private key)"
                                   : "--tls-key needs --tls-cert FILE (the certificate it signs)");
    if (is_loopback_host(options.host)) return Ok{};
    std::string missing;
    if (!options.token) missing = "a token (--token-file FILE)";
    if (!has_cert)
        missing += std::string(missing.empty() ? "" : " and ") + "TLS (--tls-cert FILE --tls-key FILE)";
    if (missing.empty()) return Ok{};
    return make_error("refusing to listen on non-loopback address '" + options.host +
                      "': remote use requires authentication and encryption; missing " + missing);
}

}  // namespace lc::bake

#pragma once
// TLS settings for the channel: the server's certificate and key, the client's
// trust anchors. TLS 1.2 is the oldest version either side accepts.
#include <filesystem>
#include <memory>

#include "lightcuts/result.h"
#include "protocol/transport.h"

namespace lc {

// The server presents `certificate` (PEM, the chain leaf first) signed by `private_key` (PEM).
Result<std::shared_ptr<asio::ssl::context>> make_tls_server_context(const std::filesystem::path& certificate,
                                                                    const std::filesystem::path& private_key);

// The client verifies the server against `ca_file` (PEM: a CA, or the server's
// self-signed certificate itself), or the system's trust store when it is empty.
Result<std::shared_ptr<asio::ssl::context>> make_tls_client_context(const std::filesystem::path& ca_file);

}  // namespace lc

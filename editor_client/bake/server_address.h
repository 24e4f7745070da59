#pragma once
// How the client reaches a server: "HOST:PORT" (IPv6 in brackets) and the
// token file a server off loopback asks for. Shared by bake and server-status.
#include <filesystem>
#include <string>

#include "lightcuts/result.h"

namespace lc::client {

// False when `text` is not HOST:PORT with a numeric port.
bool split_host_port(const std::string& text, std::string& host, std::string& port);

// The token on the file's first line (trailing blanks dropped); "" for an empty path.
Result<std::string> read_token(const std::filesystem::path& path);

}  // namespace lc::client

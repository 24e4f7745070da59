#pragma once
// HOST:PORT as both programs take it (`--listen`, `--server`, server-status):
// one parser, so the server and the client accept and refuse the same text.
#include <cstdint>
#include <string>
#include <string_view>

#include "lightcuts/result.h"

namespace lc {

struct Endpoint {
    std::string host;  // an IPv6 literal without its brackets
    uint16_t port = 0;
};

// "127.0.0.1:7000", "[::1]:7000", "name:0". Refuses a missing host or port,
// anything but decimal digits in the port, and ports over 65535, naming the text.
Result<Endpoint> parse_endpoint(std::string_view text);

}  // namespace lc

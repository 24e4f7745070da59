#include "protocol/endpoint.h"

namespace lc {
namespace {

Error bad_endpoint(std::string_view text, std::string_view why) {
    return make_error("address must be HOST:PORT (" + std::string(why) + "), got '" + std::string(text) + "'");
}

// Decimal digits only, at most 65535; no sign, no spaces.
bool parse_port(std::string_view digits, uint16_t& port) {
    if (digits.empty() || digits.size() > 5) return false;
    uint32_t value = 0;
    for (char c : digits) {
        if (c < '0' || c > '9') return false;
        value = value * 10 + static_cast<uint32_t>(c - '0');
    }
    if (value > 65535) return false;
    port = static_cast<uint16_t>(value);
    return true;
}

}  // namespace

Result<Endpoint> parse_endpoint(std::string_view text) {
    const size_t colon = text.rfind(':');
    if (colon == std::string_view::npos) return bad_endpoint(text, "no port");
    Endpoint endpoint;
    std::string_view host = text.substr(0, colon);
    if (host.size() > 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
    if (host.empty()) return bad_endpoint(text, "no host");
    if (!parse_port(text.substr(colon + 1), endpoint.port)) return bad_endpoint(text, "the port is not 0 to 65535");
    endpoint.host = std::string(host);
    return endpoint;
}

}  // namespace lc

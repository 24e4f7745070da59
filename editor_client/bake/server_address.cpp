#include "editor_client/bake/server_address.h"

#include <cstdio>

namespace lc::client {

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

}  // namespace lc::client

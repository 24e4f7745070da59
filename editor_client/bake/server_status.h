#pragma once
// Asks a lightmass_server how it is (editor_client server-status): connects
// (TLS when asked), says Hello with the token, sends StatusRequest and returns
// the StatusReply, all within one deadline. A server that refuses (wrong
// token, another protocol version) is reported in its own words.
#include <filesystem>
#include <string>

#include "lightcuts/result.h"
#include "protocol/messages.h"

namespace lc::client {

struct ServerStatusQuery {
    std::string server;  // HOST:PORT
    std::filesystem::path token_file;
    bool tls = false;
    std::filesystem::path tls_ca_file;  // empty: the system's trusted CAs
    double timeout_seconds = 10.0;
};

Result<StatusReplyMsg> query_server_status(const ServerStatusQuery& query);

}  // namespace lc::client

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

// Where a query's time went, in milliseconds: TCP connect (and TLS handshake),
// Hello to HelloAck, StatusRequest to StatusReply (the server's part).
struct ServerStatusTiming {
    double connect_ms = 0.0;
    double hello_ms = 0.0;
    double status_ms = 0.0;
};

struct ServerStatusQuery {
    std::string server;  // HOST:PORT
    std::filesystem::path token_file;
    bool tls = false;
    std::filesystem::path tls_ca_file;  // empty: the system's trusted CAs
    double timeout_seconds = 10.0;
    ServerStatusTiming* timing = nullptr;  // filled as the query goes, when set
};

Result<StatusReplyMsg> query_server_status(const ServerStatusQuery& query);

}  // namespace lc::client

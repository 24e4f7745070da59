#pragma once
// A StatusReply as editor_client server-status prints it: a few lines for
// people, or JSON for machines (sizes in bytes there, MiB in the text).
#include <nlohmann/json.hpp>

#include <string>

#include "protocol/messages.h"

namespace lc::client {

std::string server_status_text(const StatusReplyMsg& status);
nlohmann::json server_status_json(const StatusReplyMsg& status);

}  // namespace lc::client

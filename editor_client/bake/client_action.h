#pragma once
// What ClientSession asks of the I/O layer besides the messages it sends, as
// ServerSession's actions ask of connection.cpp: the session decides, and
// bake_client.cpp applies them (ClientOutputs) in the order they come, so the
// session touches no file and calls no callback.
#include <cstdint>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "protocol/messages.h"

namespace lc::client {

namespace client_action {

// The server's progress, or the client's own while the result arrives.
struct ReportProgress {
    ProgressMsg progress;
};
struct ReportWarning {
    std::string text;
};
// --record: a channel sent or received, whole.
struct RecordChannel {
    std::string name;
    std::vector<uint8_t> bytes;
};
// bake -o: the result channel goes into a dump as it arrives (DumpWriter).
struct OpenDump {
    std::string channel_name;
    uint64_t total_bytes = 0;
};
// A view of the message the session was given: valid until the session is next called.
struct AppendDump {
    std::span<const uint8_t> bytes;
};
// The tree is valid: the dump takes its place (the bake fails if this fails).
struct CommitDump {};
// The bake failed: an open dump is dropped, and an earlier file at its path stays.
struct DiscardDump {};

}  // namespace client_action

using ClientAction =
    std::variant<client_action::ReportProgress, client_action::ReportWarning, client_action::RecordChannel,
                 client_action::OpenDump, client_action::AppendDump, client_action::CommitDump,
                 client_action::DiscardDump>;
using ClientActions = std::vector<ClientAction>;

}  // namespace lc::client

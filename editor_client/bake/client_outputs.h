#pragma once
// The I/O layer's side of ClientSession's actions (client_action.h): shows
// progress and warnings through the bake's callbacks, records channels
// (--record) and writes the result's dump (bake -o) with a DumpWriter.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "editor_client/bake/client_action.h"
#include "lightcuts/result.h"
#include "protocol/channel_recorder.h"
#include "protocol/dump.h"
#include "protocol/messages.h"

namespace lc::client {

struct ClientOutputsOptions {
    std::filesystem::path result_dump;          // where OpenDump writes
    const ChannelRecorder* recorder = nullptr;  // where RecordChannel writes
    std::function<void(const ProgressMsg&)> on_progress;
    std::function<void(const std::string&)> on_warning;
};

class ClientOutputs {
public:
    explicit ClientOutputs(ClientOutputsOptions options) : options_(std::move(options)) {}

    // Applies `actions` in order and stops at the first that fails: its error
    // goes to ClientSession::fail_outputs.
    Status apply(const ClientActions& actions);
    // How long the last CommitDump took (the fsync of what the stream wrote).
    double commit_ms() const { return commit_ms_; }

private:
    Status apply_one(const ClientAction& action);
    Status open_dump(const client_action::OpenDump& open);
    Status commit_dump();

    ClientOutputsOptions options_;
    std::optional<DumpWriter> dump_;
    double commit_ms_ = 0.0;
};

}  // namespace lc::client

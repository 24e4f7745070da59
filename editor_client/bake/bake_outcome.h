#pragma once
// What a finished bake hands back: the tree, the server's BakeDone, the raw
// result channel when asked for, the warnings and where the time went. Made
// by ClientSession, timed by the I/O layer (bake_client.h).
#include <string>
#include <vector>

#include "lightcuts/tree/light_tree.h"
#include "protocol/messages.h"

namespace lc::client {

struct BakeOutcome {
    LightTree tree;
    BakeDoneMsg done;
    std::string result_channel_name;
    std::vector<uint8_t> result_channel;  // the raw channel bytes (for -o dumps)
    std::vector<std::string> warnings;
    double total_ms = 0.0;
    double upload_ms = 0.0;
    double download_ms = 0.0;
    double write_ms = 0.0;   // committing the result dump: the fsync of what the stream wrote
    double import_ms = 0.0;  // the tree's structure check once its last record arrived
};

}  // namespace lc::client

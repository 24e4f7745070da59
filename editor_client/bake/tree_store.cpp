#include "editor_client/bake/tree_store.h"

#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/dump.h"

namespace lc::client {

// The bake's reader validated every record as it arrived and the structure
// at the end (ResultChannelReader::finish): the tree is not checked twice.
Status TreeStore::import(Result<BakeOutcome> outcome) {
    if (!outcome) return outcome.failure();
    tree_ = std::make_shared<const LightTree>(std::move(outcome->tree));
    ++generation_;
    return Ok{};
}

// The channel goes straight from the file into the reader, a chunk at a time:
// the payload and the decoded tree are never both held.
Status TreeStore::import_dump(const std::filesystem::path& path) {
    ResultChannelReader reader;
    Status read = read_dump_streaming(
        path,
        [](const DumpHeader& header) -> Status {
            auto name = ChannelName::parse(header.channel_name);
            if (!name || name->version != kLightcutsVersionGuid ||
                name->extension != kLightcutsExtension)
                return make_error("channel '" + header.channel_name +
                                  "' is not a Lightcuts result channel");
            return Ok{};
        },
        [&](std::span<const uint8_t> chunk) { return reader.consume(chunk); });
    if (!read) return make_error(path.string() + ": " + read.error());
    Result<LightTree> tree = reader.finish();
    if (!tree) return make_error(path.string() + ": " + tree.error());
    tree_ = std::make_shared<const LightTree>(std::move(tree.value()));
    ++generation_;
    return Ok{};
}

}  // namespace lc::client

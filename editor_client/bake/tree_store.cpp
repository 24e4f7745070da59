#include "editor_client/bake/tree_store.h"

#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/dump.h"

namespace lc::client {

Status TreeStore::import(Result<BakeOutcome> outcome) {
    if (!outcome) return outcome.failure();
    Status valid = validate_tree(outcome->tree);
    if (!valid) return make_error("received tree is invalid: " + valid.error());
    tree_ = std::make_shared<const LightTree>(std::move(outcome->tree));
    ++generation_;
    return Ok{};
}

Status TreeStore::import_dump(const std::filesystem::path& path) {
    Result<ChannelDump> dump = read_dump(path);
    if (!dump) return make_error(path.string() + ": " + dump.error());
    auto name = ChannelName::parse(dump->channel_name);
    if (!name || name->version != kLightcutsVersionGuid || name->extension != kLightcutsExtension)
        return make_error(path.string() + ": channel '" + dump->channel_name + "' is not a Lightcuts result channel");
    Result<LightTree> tree = decode_result_channel(dump->payload);
    if (!tree) return make_error(path.string() + ": " + tree.error());
    tree_ = std::make_shared<const LightTree>(std::move(tree.value()));
    ++generation_;
    return Ok{};
}

}  // namespace lc::client

#pragma once
// Channel payloads: an int32 little-endian count, then fixed-size records.
//   scene channel : count, then one SceneLightRecord per light
//   result channel: count, then per tree node FLightData, FPointLightData,
//                   LightcutsNodeRecord (the thesis's layout plus our record)
// Writers produce bounded chunks; readers are push parsers that validate every
// record as it arrives, so a 10^6-light channel never needs to be held twice.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/tree/light_tree.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_light.h"
#include "protocol/tree_links.h"

namespace lc {

// Size limits (documented in docs/PROTOCOL.md).
inline constexpr uint32_t kMaxSceneLights = 1u << 24;  // 16,777,216
inline constexpr uint32_t kMaxTreeNodes = 2u * kMaxSceneLights - 1u;
inline constexpr size_t kDefaultChunkBytes = 1u << 20;  // bytes of channel data per WriteChannel

size_t scene_record_bytes();
size_t result_record_bytes();  // FLightData + FPointLightData + LightcutsNodeRecord

// Whole-channel encoders (used for dumps and small scenes).
std::vector<uint8_t> encode_scene_channel(std::span<const SceneLight> lights);
std::vector<uint8_t> encode_result_channel(const LightTree& tree);

// Incremental result encoder: the count prefix, then records [first, first+count).
std::vector<uint8_t> encode_result_prefix(uint32_t node_count);
void append_result_records(const LightTree& tree, size_t first, size_t count,
                           std::vector<uint8_t>& out);
// The same records written to `out`, which holds exactly count * result_record_bytes().
void write_result_records(const LightTree& tree, size_t first, size_t count, std::span<uint8_t> out);

// Validates one light: finite values, non-negative colour and intensity,
// known type, unit direction for oriented lights, 0 <= inner < outer <= pi/2,
// range >= 0. The message names the light (index and GUID) and the field.
Status validate_scene_light(const SceneLight& light, size_t index);

class SceneChannelReader {
public:
    // Pushes channel bytes; fails on a bad count (negative or above the limit)
    // or a bad record, naming it.
    Status consume(std::span<const uint8_t> bytes);
    // Succeeds only when exactly `count` records arrived and nothing more.
    Result<std::vector<SceneLight>> finish();
    uint64_t bytes_seen() const { return bytes_seen_; }

private:
    std::vector<uint8_t> pending_;
    int64_t expected_ = -1;
    uint64_t bytes_seen_ = 0;
    std::vector<SceneLight> lights_;
    bool failed_ = false;
};

// What a ResultChannelReader keeps of each record once it passed validation.
enum class TreeImport {
    kNodes,         // the decoded tree: a LightTreeNode per record, for rendering and the editor
    kValidateOnly,  // only the links the structure check needs: for `bake`, which writes the dump
};

class ResultChannelReader {
public:
    explicit ResultChannelReader(TreeImport import = TreeImport::kNodes) : import_(import) {}

    Status consume(std::span<const uint8_t> bytes);
    // Checks the count, then the structure: child indices in range and greater
    // than the parent's (breadth-first order), every node but the root with one
    // parent, representatives are leaves inside the node's subtree, values finite.
    // Only for TreeImport::kNodes.
    Result<LightTree> finish();
    // The same checks for TreeImport::kValidateOnly; the tree is then known
    // valid, its records are not kept.
    Status finish_validation();
    size_t nodes_received() const { return links_.size(); }
    int64_t nodes_expected() const { return expected_; }
    uint32_t leaf_count() const { return leaf_count_; }

private:
    Status finish_structure();

    TreeImport import_;
    std::vector<uint8_t> pending_;
    int64_t expected_ = -1;
    std::vector<LightTreeNode> nodes_;  // TreeImport::kNodes only
    std::vector<NodeLinks> links_;      // gathered as the records arrive, for the structure check
    uint32_t leaf_count_ = 0;
    bool failed_ = false;
};

// Convenience: whole-buffer decoders built on the readers.
Result<std::vector<SceneLight>> decode_scene_channel(std::span<const uint8_t> bytes);
Result<LightTree> decode_result_channel(std::span<const uint8_t> bytes);

// Structural validation shared by the reader and by tests.
Status validate_tree(const LightTree& tree);

}  // namespace lc

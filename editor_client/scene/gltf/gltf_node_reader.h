#pragma once
// The fast path of glTF import: simdjson's On-Demand API reads the JSON's
// `nodes`, `scenes` and KHR_lights_punctual `lights` straight into a
// GltfNodeTable and hands back the rest of the document, those three arrays
// emptied, for tinygltf (meshes, materials, buffers, cameras). A million-light
// file then never becomes a million tinygltf objects.
//
// The reader takes only the plain form our writer and common exporters
// write: the fields the loader reads, with the JSON types tinygltf accepts
// without a second thought. Anything else (another field, a number where an
// integer belongs, an empty matrix, a syntax error) returns nullopt and the
// caller reads the whole file with tinygltf, so the loader's result and its
// messages are the same on both paths.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>

#include "editor_client/scene/gltf/gltf_node_table.h"

namespace lc::client {

struct GltfNodeSplit {
    GltfNodeTable table;
    // The file (.gltf text or .glb container) with `nodes`, `scenes` and the
    // lights replaced by [].
    std::string remainder;
};

// Told, as the reader goes, that it will not read the file's bytes before an
// offset again (the loader releases a mapped file's pages behind it).
using ConsumedBytes = std::function<void(size_t offset)>;

// A .gltf or .glb file's bytes. The JSON is read in one pass, the three
// arrays a run of elements at a time (gltf_json_sections.h), so the parser
// never indexes the whole document.
std::optional<GltfNodeSplit> read_gltf_nodes(std::span<const uint8_t> file,
                                             const ConsumedBytes& on_consumed = {});

}  // namespace lc::client

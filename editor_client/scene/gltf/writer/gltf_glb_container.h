#pragma once
// The GLB container (glTF 2.0 binary): a 12-byte header ("glTF", version 2,
// total length), a JSON chunk padded with spaces to 4 bytes, and an optional
// BIN chunk padded with zeros. Decoding checks every length against the
// file's before reading; errors start with the file's name.
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lightcuts/result.h"

namespace lc::client {

// Whether `bytes` start with the GLB magic ("glTF").
bool is_glb(std::span<const uint8_t> bytes);

// A GLB file of `json` and, unless empty, `bin` as its binary chunk.
std::vector<uint8_t> encode_glb(std::string json, std::span<const uint8_t> bin);

struct GlbChunks {
    std::string_view json;     // into the decoded bytes
    std::vector<uint8_t> bin;  // the first BIN chunk after the JSON, as stored (padding included)
};

// The chunks of the GLB in `bytes`; `file` names it in errors.
Result<GlbChunks> decode_glb(std::span<const uint8_t> bytes, const std::string& file);

}  // namespace lc::client

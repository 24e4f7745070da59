#include "editor_client/scene/gltf/gltf_buffer_sizes.h"

#include <nlohmann/json.hpp>

#include <cstring>
#include <string_view>

namespace lc::client {
namespace {

constexpr size_t kGlbHeaderBytes = 12;
constexpr size_t kChunkHeaderBytes = 8;

uint32_t read_u32(const uint8_t* bytes) {
    uint32_t value = 0;
    std::memcpy(&value, bytes, sizeof value);  // glTF is little-endian, as is every target here
    return value;
}

// The JSON text: the whole file, or a .glb's first chunk.
std::string_view json_text(std::span<const uint8_t> gltf) {
    const auto* chars = reinterpret_cast<const char*>(gltf.data());
    if (gltf.size() < 4 || std::memcmp(gltf.data(), "glTF", 4) != 0) return {chars, gltf.size()};
    if (gltf.size() < kGlbHeaderBytes + kChunkHeaderBytes) return {};
    const uint64_t length = read_u32(gltf.data() + kGlbHeaderBytes);
    if (std::memcmp(gltf.data() + kGlbHeaderBytes + 4, "JSON", 4) != 0 ||
        length > gltf.size() - kGlbHeaderBytes - kChunkHeaderBytes)
        return {};
    return {chars + kGlbHeaderBytes + kChunkHeaderBytes, size_t(length)};
}

}  // namespace

std::vector<BufferFileSize> external_buffer_sizes(std::span<const uint8_t> gltf) {
    std::vector<BufferFileSize> sizes;
    const nlohmann::json document = nlohmann::json::parse(json_text(gltf), nullptr, false);
    if (!document.is_object() || !document.contains("buffers") || !document["buffers"].is_array())
        return sizes;
    for (const nlohmann::json& buffer : document["buffers"]) {
        if (!buffer.is_object() || !buffer.contains("uri") || !buffer["uri"].is_string()) continue;
        if (!buffer.contains("byteLength") || !buffer["byteLength"].is_number_unsigned()) continue;
        const std::string& uri = buffer["uri"].get_ref<const std::string&>();
        if (uri.starts_with("data:")) continue;
        sizes.push_back({uri, buffer["byteLength"].get<uint64_t>()});
    }
    return sizes;
}

}  // namespace lc::client

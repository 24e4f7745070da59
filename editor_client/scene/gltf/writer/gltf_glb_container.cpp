#include "editor_client/scene/gltf/writer/gltf_glb_container.h"

namespace lc::client {
namespace {

constexpr uint32_t kGlbMagic = 0x46546C67u;      // "glTF"
constexpr uint32_t kGlbChunkJson = 0x4E4F534Au;  // "JSON"
constexpr uint32_t kGlbChunkBin = 0x004E4942u;   // "BIN\0"

void append_u32(std::vector<uint8_t>& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}

uint32_t read_u32(const uint8_t* p) {
    return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}

// The header's declared length, checked against the file's.
Result<uint32_t> checked_length(std::span<const uint8_t> bytes, const std::string& file) {
    if (bytes.size() < 20) return make_error(file + ": truncated glTF binary header");
    const uint32_t version = read_u32(bytes.data() + 4);
    const uint32_t length = read_u32(bytes.data() + 8);
    if (version != 2) {
        return make_error(file + ": glTF binary version " + std::to_string(version) + " (expected 2)");
    }
    if (length > bytes.size()) {
        return make_error(file + ": glTF binary claims " + std::to_string(length) +
                          " bytes but the file has " + std::to_string(bytes.size()));
    }
    return length;
}

}  // namespace

bool is_glb(std::span<const uint8_t> bytes) {
    return bytes.size() >= 4 && read_u32(bytes.data()) == kGlbMagic;
}

std::vector<uint8_t> encode_glb(std::string json, std::span<const uint8_t> bin) {
    while (json.size() % 4 != 0) json += ' ';
    const size_t bin_padded = (bin.size() + 3) / 4 * 4;
    const size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin_padded);
    std::vector<uint8_t> out;
    out.reserve(total);
    append_u32(out, kGlbMagic);
    append_u32(out, 2);
    append_u32(out, uint32_t(total));
    append_u32(out, uint32_t(json.size()));
    append_u32(out, kGlbChunkJson);
    out.insert(out.end(), json.begin(), json.end());
    if (!bin.empty()) {
        append_u32(out, uint32_t(bin_padded));
        append_u32(out, kGlbChunkBin);
        out.insert(out.end(), bin.begin(), bin.end());
        out.resize(out.size() + (bin_padded - bin.size()), 0);
    }
    return out;
}

Result<GlbChunks> decode_glb(std::span<const uint8_t> bytes, const std::string& file) {
    Result<uint32_t> length = checked_length(bytes, file);
    if (!length) return length.failure();
    GlbChunks out;
    bool have_json = false;
    for (size_t at = 12; at + 8 <= *length;) {
        const uint32_t chunk_length = read_u32(bytes.data() + at);
        const uint32_t chunk_type = read_u32(bytes.data() + at + 4);
        if (chunk_length > *length - at - 8)
            return make_error(file + ": glTF binary chunk runs past the end");
        const uint8_t* data = bytes.data() + at + 8;
        if (!have_json) {
            if (chunk_type != kGlbChunkJson)
                return make_error(file + ": the first glTF binary chunk is not JSON");
            out.json = std::string_view(reinterpret_cast<const char*>(data), chunk_length);
            have_json = true;
        } else if (chunk_type == kGlbChunkBin && out.bin.empty()) {
            out.bin.assign(data, data + chunk_length);
        }
        at += 8 + size_t(chunk_length);
    }
    if (!have_json) return make_error(file + ": glTF binary without a JSON chunk");
    return out;
}

}  // namespace lc::client

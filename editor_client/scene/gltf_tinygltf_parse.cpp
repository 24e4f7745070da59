#include "editor_client/scene/gltf_tinygltf_parse.h"

#include <cstring>
#include <exception>
#include <sstream>
#include <string>
#include <vector>

#include "editor_client/scene/gltf_accessor.h"
#include "editor_client/scene/gltf_buffer_sizes.h"
#include "editor_client/scene/gltf_resource_access.h"

namespace lc::client {
namespace {

namespace tg = tinygltf;

std::string trim(std::string s) {
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' ')) s.pop_back();
    size_t start = 0;
    while (start < s.size() && (s[start] == '\n' || s[start] == ' ')) ++start;
    return s.substr(start);
}

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        line = trim(line);
        if (!line.empty()) lines.push_back(line);
    }
    return lines;
}

// tinygltf quotes whole data URIs in its messages; keep them readable.
std::string shorten_data_uris(std::string message) {
    size_t at = 0;
    while ((at = message.find("data:", at)) != std::string::npos) {
        size_t end = message.find_first_of(" \n\"'", at);
        if (end == std::string::npos) end = message.size();
        if (end - at > 48) {
            message.replace(at + 40, end - at - 40, "...(" + std::to_string(end - at) + " chars)");
        }
        at += 40;
    }
    return message;
}

// tinygltf decodes images through this callback. It reads an image's
// bufferView bytes without checking them against the buffer, so we check
// first.
struct ImageLoadContext {
    const tg::Model* model = nullptr;
};

// Why an image's bufferView lies outside its buffer; empty when it does not.
std::string image_view_outside(const tg::Model& model, const tg::Image& image, int image_index) {
    if (image.bufferView < 0) return {};
    const tg::BufferView& view = model.bufferViews[size_t(image.bufferView)];
    const tg::Buffer& buffer = model.buffers[size_t(view.buffer)];
    if (byte_range_fits(view.byteOffset, view.byteLength, buffer.data.size())) return {};
    return "image " + std::to_string(image_index) + ": bufferView " + std::to_string(image.bufferView) +
           " (offset " + std::to_string(view.byteOffset) + ", length " + std::to_string(view.byteLength) +
           ") lies outside buffer " + std::to_string(view.buffer) + " (" +
           std::to_string(buffer.data.size()) + " bytes)\n";
}

bool load_image_checked(tg::Image* image, const int image_index, std::string* err, std::string* warn,
                        int req_width, int req_height, const unsigned char* bytes, int size, void* user) {
    const auto* ctx = static_cast<const ImageLoadContext*>(user);
    const std::string outside = image_view_outside(*ctx->model, *image, image_index);
    if (!outside.empty()) {
        if (err) *err += outside;
        return false;
    }
    if (bytes == nullptr || size <= 0) {
        if (warn) *warn += "image " + std::to_string(image_index) + " has no data\n";
        return true;
    }
    std::string decode_error;
    if (!tg::LoadImageData(image, image_index, &decode_error, warn, req_width, req_height, bytes, size,
                           nullptr)) {
        if (warn) {
            *warn += "image " + std::to_string(image_index) +
                     " could not be decoded; its textures are ignored: " + trim(decode_error) + "\n";
        }
        image->image.clear();
    }
    return true;
}

// tinygltf's error as ours: readable data: URIs, a hint for bad base64, the refusals.
std::string rejection_message(const std::string& err, const GltfResourceAccess& access) {
    std::string message = shorten_data_uris(trim(err));
    if (message.empty()) message = "tinygltf rejected the file without a message";
    if (message.find("Failed to decode 'uri'") != std::string::npos) {
        message += " (corrupt base64, or not as long as the buffer's byteLength)";
    }
    for (const std::string& refusal : access.refusals()) message += "; refused: " + refusal;
    return message;
}

}  // namespace

Status parse_with_tinygltf(std::span<const uint8_t> bytes, const std::filesystem::path& resource_folder,
                           bool allow_external, tg::Model& model, GltfDiagnostics& diagnostics) {
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    const auto length = static_cast<unsigned int>(bytes.size());
    tg::TinyGLTF gltf;
    ImageLoadContext image_context{&model};
    gltf.SetImageLoader(&load_image_checked, &image_context);
    GltfResourceAccess access(resource_folder, allow_external);
    access.expect_buffer_sizes(external_buffer_sizes(bytes));
    gltf.SetFsCallbacks(access.callbacks());
    const std::string base_dir = resource_folder.string();
    std::string err;
    std::string warn_text;
    bool ok = false;
    try {
        ok = binary ? gltf.LoadBinaryFromMemory(&model, &err, &warn_text, bytes.data(), length, base_dir)
                    : gltf.LoadASCIIFromString(&model, &err, &warn_text,
                                               reinterpret_cast<const char*>(bytes.data()), length, base_dir);
    } catch (const std::exception& e) {
        // tinygltf throws on some malformed inputs (e.g. .at() on an empty chunk).
        return diagnostics.fail(std::string("malformed glTF: ") + e.what());
    }
    for (const std::string& line : split_lines(warn_text)) diagnostics.warn(line);
    if (!ok) {
        return diagnostics.fail(std::string(binary ? "invalid glTF binary: " : "invalid glTF: ") +
                                rejection_message(err, access));
    }
    // Refused images are dropped with tinygltf's warning; say why.
    for (const std::string& refusal : access.refusals()) diagnostics.warn("refused: " + refusal);
    return Ok{};
}

}  // namespace lc::client

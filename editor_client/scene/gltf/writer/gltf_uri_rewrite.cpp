#include "editor_client/scene/gltf/writer/gltf_uri_rewrite.h"

#include <cctype>
#include <string>

#include "editor_client/scene/gltf/gltf_environment.h"

namespace lc::client {
namespace {

bool is_relative_uri(const std::string& uri) {
    if (uri.empty() || uri.rfind("data:", 0) == 0 || uri.front() == '/') return false;
    return uri.find("://") == std::string::npos;
}

std::string percent_decode(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

std::string percent_encode_path(const std::string& path) {
    std::string out;
    for (unsigned char c : path) {
        if (c == ' ' || c == '%' || c == '#' || c == '?') {
            static constexpr char kHex[] = "0123456789ABCDEF";
            out += '%';
            out += kHex[c >> 4];
            out += kHex[c & 15];
        } else {
            out += char(c);
        }
    }
    return out;
}

}  // namespace

void rewrite_uris(nlohmann::json& doc, const std::filesystem::path& source,
                  const std::filesystem::path& out) {
    const std::filesystem::path from = std::filesystem::absolute(source).parent_path().lexically_normal();
    const std::filesystem::path to = std::filesystem::absolute(out).parent_path().lexically_normal();
    if (from == to) return;
    for (const char* key : {"buffers", "images"}) {
        if (!doc.contains(key) || !doc[key].is_array()) continue;
        for (nlohmann::json& item : doc[key]) {
            if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
            const std::string uri = item["uri"].get<std::string>();
            if (!is_relative_uri(uri)) continue;
            const std::filesystem::path target = (from / percent_decode(uri)).lexically_normal();
            std::filesystem::path relative = target.lexically_relative(to);
            if (relative.empty()) relative = target;
            item["uri"] = percent_encode_path(relative.generic_string());
        }
    }
    // The environment's image is a path, not a URI (gltf_environment.h).
    if (doc.contains("asset") && doc["asset"].is_object() && doc["asset"].contains("extras") &&
        doc["asset"]["extras"].is_object() && doc["asset"]["extras"].contains(kEnvironmentExtrasKey)) {
        nlohmann::json& map = doc["asset"]["extras"][kEnvironmentExtrasKey];
        if (map.is_object() && map.contains("image") && map["image"].is_string()) {
            const std::filesystem::path image(map["image"].get<std::string>());
            if (image.is_relative()) map["image"] = path_from(to, from / image);
        }
    }
}

}  // namespace lc::client

// Replacing the lights of an existing glTF. We edit its JSON (nlohmann)
// rather than go through tinygltf: every other field, extension and
// external file must stay exactly as it was, which a parse-and-reserialise
// round trip through tinygltf's model does not keep.
#include "editor_client/scene/gltf/writer/gltf_light_patcher.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <set>
#include <string>
#include <vector>

#include "editor_client/scene/gltf/writer/gltf_document_output.h"
#include "editor_client/scene/gltf/writer/gltf_glb_container.h"
#include "editor_client/scene/gltf/gltf_json_values.h"
#include "editor_client/scene/gltf/writer/gltf_light_json.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/gltf/writer/gltf_uri_rewrite.h"

namespace lc::client {
namespace {

using json = nlohmann::json;

struct SourceDocument {
    json doc;
    std::vector<uint8_t> bin;  // a .glb's binary chunk
    bool binary = false;
};

Result<SourceDocument> read_source(const std::filesystem::path& source) {
    std::ifstream file(source, std::ios::binary);
    if (!file) return make_error(source.string() + ": cannot open the file");
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                                     std::istreambuf_iterator<char>());
    SourceDocument out;
    std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (is_glb(bytes)) {
        out.binary = true;
        Result<GlbChunks> chunks = decode_glb(bytes, source.string());
        if (!chunks) return chunks.failure();
        text = chunks->json;
        out.bin = std::move(chunks->bin);
    }
    out.doc = json::parse(text.begin(), text.end(), nullptr, false);
    if (out.doc.is_discarded()) return make_error(source.string() + ": bad JSON");
    if (!out.doc.is_object()) return make_error(source.string() + ": the JSON root is not an object");
    return out;
}

int target_scene(const json& doc) {
    if (!doc.contains("scenes") || !doc["scenes"].is_array() || doc["scenes"].empty()) return -1;
    if (doc.contains("scene") && doc["scene"].is_number_integer()) {
        const int64_t s = doc["scene"].get<int64_t>();
        if (s >= 0 && s < int64_t(doc["scenes"].size())) return int(s);
    }
    return 0;
}

void add_children(const json& doc, std::set<int64_t>& referenced) {
    for (const json& node : doc["nodes"]) {
        if (node.is_object() && node.contains("children") && node["children"].is_array()) {
            for (const json& c : node["children"])
                if (c.is_number_integer()) referenced.insert(c.get<int64_t>());
        }
    }
}

void add_skin_nodes(const json& doc, std::set<int64_t>& referenced) {
    if (!doc.contains("skins") || !doc["skins"].is_array()) return;
    for (const json& skin : doc["skins"]) {
        if (!skin.is_object()) continue;
        if (skin.contains("skeleton") && skin["skeleton"].is_number_integer())
            referenced.insert(skin["skeleton"].get<int64_t>());
        if (skin.contains("joints") && skin["joints"].is_array())
            for (const json& j : skin["joints"])
                if (j.is_number_integer()) referenced.insert(j.get<int64_t>());
    }
}

void add_animated_nodes(const json& doc, std::set<int64_t>& referenced) {
    if (!doc.contains("animations") || !doc["animations"].is_array()) return;
    for (const json& anim : doc["animations"]) {
        if (!anim.is_object() || !anim.contains("channels") || !anim["channels"].is_array()) continue;
        for (const json& ch : anim["channels"]) {
            if (ch.is_object() && ch.contains("target") && ch["target"].is_object() &&
                ch["target"].contains("node") && ch["target"]["node"].is_number_integer())
                referenced.insert(ch["target"]["node"].get<int64_t>());
        }
    }
}

// Nodes we must not reuse: children, skin joints, animation targets.
std::set<int64_t> referenced_nodes(const json& doc) {
    std::set<int64_t> referenced;
    add_children(doc, referenced);
    add_skin_nodes(doc, referenced);
    add_animated_nodes(doc, referenced);
    return referenced;
}

std::set<int64_t> scene_root_set(const json& doc, int scene_index) {
    std::set<int64_t> in_scene;
    if (scene_index < 0) return in_scene;
    const json& scene = doc["scenes"][size_t(scene_index)];
    if (scene.is_object() && scene.contains("nodes") && scene["nodes"].is_array())
        for (const json& n : scene["nodes"])
            if (n.is_number_integer()) in_scene.insert(n.get<int64_t>());
    return in_scene;
}

// Strips every light reference from the nodes; returns the nodes that held
// nothing else, may be reused, in order.
std::vector<size_t> strip_light_references(json& doc, int scene_index) {
    const std::set<int64_t> referenced = referenced_nodes(doc);
    const std::set<int64_t> in_scene = scene_root_set(doc, scene_index);
    json& nodes = doc["nodes"];
    std::vector<size_t> reusable;
    for (size_t i = 0; i < nodes.size(); ++i) {
        json& node = nodes[i];
        if (!node.is_object() || !node.contains("extensions") || !node["extensions"].is_object() ||
            !node["extensions"].contains(kLightsPunctualExtension)) {
            continue;
        }
        node["extensions"].erase(kLightsPunctualExtension);
        if (node["extensions"].empty()) node.erase("extensions");
        if (node.contains("extras") && node["extras"].is_object()) {
            node["extras"].erase(kGuidExtrasKey);
            node["extras"].erase(kClassicExtrasKey);
            if (node["extras"].empty()) node.erase("extras");
        }
        const bool bare = !node.contains("mesh") && !node.contains("camera") && !node.contains("children") &&
                          !node.contains("skin") && !node.contains("weights") && !node.contains("extensions");
        const bool root_of_scene = scene_index < 0 || in_scene.count(int64_t(i)) > 0;
        if (bare && root_of_scene && referenced.count(int64_t(i)) == 0) reusable.push_back(i);
    }
    return reusable;
}

// Each light's node in a reusable node, else appended to the nodes and the scene.
void place_light_nodes(json& doc, std::span<const SceneLight> lights, const std::vector<size_t>& reusable,
                       int scene_index) {
    json& nodes = doc["nodes"];
    for (size_t k = 0; k < lights.size(); ++k) {
        json node = light_node_json(lights[k], k);
        if (k < reusable.size()) {
            nodes[reusable[k]] = std::move(node);
            continue;
        }
        nodes.push_back(std::move(node));
        if (scene_index >= 0) {
            json& scene = doc["scenes"][size_t(scene_index)];
            if (!scene.contains("nodes") || !scene["nodes"].is_array()) scene["nodes"] = json::array();
            scene["nodes"].push_back(nodes.size() - 1);
        }
    }
}

// Leftover light-only nodes at the end of the array are dropped (nothing but
// scene lists can name them); others keep their place, emptied, so that no
// index in the file changes.
void drop_leftover_nodes(json& doc, const std::vector<size_t>& reusable, size_t used) {
    json& nodes = doc["nodes"];
    for (size_t k = reusable.size(); k-- > used;) {
        const size_t index = reusable[k];
        if (index + 1 != nodes.size()) {
            nodes[index] = json::object({{"name", "unused"}});
            continue;
        }
        nodes.erase(nodes.end() - 1);
        if (!doc.contains("scenes") || !doc["scenes"].is_array()) continue;
        for (json& scene : doc["scenes"]) {
            if (!scene.is_object() || !scene.contains("nodes") || !scene["nodes"].is_array()) continue;
            json& list = scene["nodes"];
            list.erase(std::remove(list.begin(), list.end(), json(index)), list.end());
        }
    }
}

void set_lights_extension(json& doc, std::span<const SceneLight> lights) {
    if (lights.empty()) {
        if (doc.contains("extensions") && doc["extensions"].is_object()) {
            doc["extensions"].erase(kLightsPunctualExtension);
            if (doc["extensions"].empty()) doc.erase("extensions");
        }
        remove_extension_name(doc, "extensionsUsed", kLightsPunctualExtension);
        remove_extension_name(doc, "extensionsRequired", kLightsPunctualExtension);
        return;
    }
    json light_list = json::array();
    for (size_t k = 0; k < lights.size(); ++k) light_list.push_back(light_json(lights[k], k));
    if (!doc.contains("extensions") || !doc["extensions"].is_object()) doc["extensions"] = json::object();
    doc["extensions"][kLightsPunctualExtension] = {{"lights", light_list}};
    add_extension_used(doc, kLightsPunctualExtension);
}

// A .glb's binary chunk belongs to the first buffer, the one without a uri:
// its index (-1: none, the chunk dropped), the chunk cut to its byteLength.
Result<int> keep_binary_chunk(const json& doc, SourceDocument& src, const std::filesystem::path& source) {
    int bin_buffer = -1;
    if (src.binary && doc.contains("buffers") && doc["buffers"].is_array()) {
        for (size_t b = 0; b < doc["buffers"].size(); ++b) {
            if (doc["buffers"][b].is_object() && !doc["buffers"][b].contains("uri")) {
                bin_buffer = int(b);
                break;
            }
        }
    }
    if (bin_buffer < 0) {
        src.bin.clear();
        return bin_buffer;
    }
    if (src.bin.empty()) {
        return make_error(source.string() + ": buffer " + std::to_string(bin_buffer) +
                          " has no uri but the file has no binary chunk");
    }
    // The chunk may carry padding beyond byteLength; keep exactly the buffer.
    const json& length = doc["buffers"][size_t(bin_buffer)]["byteLength"];
    if (length.is_number_unsigned() && length.get<uint64_t>() <= src.bin.size())
        src.bin.resize(size_t(length.get<uint64_t>()));
    return bin_buffer;
}

}  // namespace

Status write_lights_into_gltf(const std::filesystem::path& source, std::span<const SceneLight> lights,
                              const std::filesystem::path& out) {
    Status valid = validate_lights_for_gltf(lights);
    if (!valid) return valid;
    Result<SourceDocument> read = read_source(source);
    if (!read) return Error{read.error()};
    SourceDocument& src = *read;
    json& doc = src.doc;
    try {
        if (!doc.contains("nodes")) doc["nodes"] = json::array();
        if (!doc["nodes"].is_array()) return make_error(source.string() + ": 'nodes' is not an array");
        const int scene_index = target_scene(doc);
        const std::vector<size_t> reusable = strip_light_references(doc, scene_index);
        place_light_nodes(doc, lights, reusable, scene_index);
        drop_leftover_nodes(doc, reusable, lights.size());
        if (doc["nodes"].empty()) doc.erase("nodes");
        set_lights_extension(doc, lights);
        rewrite_uris(doc, source, out);
        Result<int> bin_buffer = keep_binary_chunk(doc, src, source);
        if (!bin_buffer) return make_error(bin_buffer.error());
        return write_gltf_document(std::move(doc), src.bin, *bin_buffer, out);
    } catch (const json::exception& e) {
        return make_error(source.string() + ": unexpected JSON structure: " + e.what());
    }
}

}  // namespace lc::client

// glTF 2.0 -> Scene. The node reader (simdjson) takes the nodes, scenes and
// punctual lights into a flat table when the file is in its plain form, and
// tinygltf parses the rest and the buffers (or everything, otherwise: the
// table is then filled from tinygltf's model). Everything neither checks
// (index ranges, accessor extents, finiteness, the node graph) is checked here
// before any byte is read, so a broken file gives an error and never a crash.
#include "editor_client/scene/gltf_loader.h"

#include <tiny_gltf.h>  // Debian's shared library: no TINYGLTF_IMPLEMENTATION here

#include <spdlog/spdlog.h>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "editor_client/scene/gltf_environment.h"
#include "editor_client/scene/gltf_node_reader.h"
#include "editor_client/scene/gltf_resource_access.h"
#include "editor_client/scene/mapped_file.h"
#include "editor_client/scene/scene_guid.h"
#include "editor_client/scene/tangent_frames.h"
#include "editor_client/scene/texture_coordinates.h"
#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

namespace tg = tinygltf;

constexpr const char* kLightsExtension = "KHR_lights_punctual";
constexpr const char* kEmissiveStrengthExtension = "KHR_materials_emissive_strength";

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

bool finite(double v) {
    return std::isfinite(v);
}

// Shortest readable form of a number for messages ("0.8", "-2", "1e+39").
std::string num(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", v);
    return text;
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

bool all_finite(std::span<const double> values) {
    return std::all_of(values.begin(), values.end(), [](double v) { return finite(v); });
}

bool all_finite(const glm::dmat4& m) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!finite(m[c][r])) return false;
    return true;
}

const char* type_name(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return "SCALAR";
        case TINYGLTF_TYPE_VEC2:
            return "VEC2";
        case TINYGLTF_TYPE_VEC3:
            return "VEC3";
        case TINYGLTF_TYPE_VEC4:
            return "VEC4";
        case TINYGLTF_TYPE_MAT2:
            return "MAT2";
        case TINYGLTF_TYPE_MAT3:
            return "MAT3";
        case TINYGLTF_TYPE_MAT4:
            return "MAT4";
    }
    return "unknown type";
}

int component_count(int type) {
    switch (type) {
        case TINYGLTF_TYPE_SCALAR:
            return 1;
        case TINYGLTF_TYPE_VEC2:
            return 2;
        case TINYGLTF_TYPE_VEC3:
            return 3;
        case TINYGLTF_TYPE_VEC4:
            return 4;
        case TINYGLTF_TYPE_MAT2:
            return 4;
        case TINYGLTF_TYPE_MAT3:
            return 9;
        case TINYGLTF_TYPE_MAT4:
            return 16;
    }
    return 0;
}

const char* component_type_name(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
            return "BYTE";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return "UNSIGNED_BYTE";
        case TINYGLTF_COMPONENT_TYPE_SHORT:
            return "SHORT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return "UNSIGNED_SHORT";
        case TINYGLTF_COMPONENT_TYPE_INT:
            return "INT";
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
            return "UNSIGNED_INT";
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return "FLOAT";
    }
    return "unknown component type";
}

int component_size(int component_type) {
    switch (component_type) {
        case TINYGLTF_COMPONENT_TYPE_BYTE:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            return 1;
        case TINYGLTF_COMPONENT_TYPE_SHORT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
            return 2;
        case TINYGLTF_COMPONENT_TYPE_INT:
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            return 4;
    }
    return 0;
}

// [offset, offset + length) fits inside `size` bytes, without overflow.
bool range_fits(size_t offset, size_t length, size_t size) {
    return offset <= size && length <= size - offset;
}

// tinygltf decodes images through this callback. It reads an image's
// bufferView bytes without checking them against the buffer, so we check
// first; an undecodable image becomes a warning (the texture is dropped), not
// a failed load.
struct ImageLoadContext {
    const tg::Model* model = nullptr;
};

bool load_image_checked(tg::Image* image, const int image_index, std::string* err,
                        std::string* warn, int req_width, int req_height,
                        const unsigned char* bytes, int size, void* user) {
    const auto* ctx = static_cast<const ImageLoadContext*>(user);
    if (image->bufferView >= 0) {
        const tg::BufferView& view = ctx->model->bufferViews[size_t(image->bufferView)];
        const tg::Buffer& buffer = ctx->model->buffers[size_t(view.buffer)];
        if (!range_fits(view.byteOffset, view.byteLength, buffer.data.size())) {
            if (err) {
                *err += "image " + std::to_string(image_index) + ": bufferView " +
                        std::to_string(image->bufferView) + " (offset " +
                        std::to_string(view.byteOffset) + ", length " +
                        std::to_string(view.byteLength) + ") lies outside buffer " +
                        std::to_string(view.buffer) + " (" + std::to_string(buffer.data.size()) +
                        " bytes)\n";
            }
            return false;
        }
    }
    if (bytes == nullptr || size <= 0) {
        if (warn) *warn += "image " + std::to_string(image_index) + " has no data\n";
        return true;
    }
    std::string decode_error;
    if (!tg::LoadImageData(image, image_index, &decode_error, warn, req_width, req_height, bytes,
                           size, nullptr)) {
        if (warn) {
            *warn += "image " + std::to_string(image_index) +
                     " could not be decoded; its textures are ignored: " + trim(decode_error) +
                     "\n";
        }
        image->image.clear();
    }
    return true;
}

// A node's or light's extras.lightcuts_classic as tinygltf parsed it.
ExtrasFlag classic_flag_of(const tg::Value& extras) {
    if (!extras.IsObject() || !extras.Has(kClassicExtrasKey)) return ExtrasFlag::kAbsent;
    const tg::Value& v = extras.Get(kClassicExtrasKey);
    if (!v.IsBool()) return ExtrasFlag::kNotBoolean;
    return v.Get<bool>() ? ExtrasFlag::kTrue : ExtrasFlag::kFalse;
}

// tinygltf's nodes, scenes and lights in the table the loader reads.
GltfNodeTable node_table_from(const tg::Model& model) {
    GltfNodeTable table;
    table.nodes.reserve(model.nodes.size());
    for (const tg::Node& in : model.nodes) {
        GltfNode node;
        node.mesh = in.mesh;
        node.camera = in.camera;
        node.first_child = uint32_t(table.children.size());
        node.child_count = uint32_t(in.children.size());
        table.children.insert(table.children.end(), in.children.begin(), in.children.end());
        node.matrix = table.add_numbers(in.matrix);
        node.translation = table.add_numbers(in.translation);
        node.rotation = table.add_numbers(in.rotation);
        node.scale = table.add_numbers(in.scale);
        auto extension = in.extensions.find(kLightsExtension);
        if (extension != in.extensions.end()) {
            const tg::Value& e = extension->second;
            const bool numbered = e.IsObject() && e.Has("light") && e.Get("light").IsNumber();
            node.light = numbered ? LightReference::kNumber : LightReference::kMalformed;
            if (numbered) node.light_number = e.Get("light").GetNumberAsDouble();
        }
        node.classic = classic_flag_of(in.extras);
        if (in.extras.IsObject() && in.extras.Has(kGuidExtrasKey)) {
            const tg::Value& v = in.extras.Get(kGuidExtrasKey);
            std::optional<Guid> guid =
                v.IsString() ? Guid::parse(v.Get<std::string>()) : std::nullopt;
            node.guid_extras = guid ? GltfNode::GuidExtras::kGuid : GltfNode::GuidExtras::kInvalid;
            if (guid) node.guid = *guid;
        }
        if (in.camera >= 0) node.name = table.add_text(in.name);
        table.nodes.push_back(node);
    }
    for (const tg::Scene& scene : model.scenes) {
        table.scenes.push_back({uint32_t(table.scene_roots.size()), uint32_t(scene.nodes.size())});
        table.scene_roots.insert(table.scene_roots.end(), scene.nodes.begin(), scene.nodes.end());
    }
    table.lights.reserve(model.lights.size());
    for (const tg::Light& in : model.lights) {
        GltfPunctualLight light;
        light.name = table.add_text(in.name);
        light.type = table.add_text(in.type);
        // Only 3 is valid; a longer list keeps a count that says it is not.
        light.color_count = uint8_t(std::min<size_t>(in.color.size(), 255));
        if (in.color.size() == 3) std::copy(in.color.begin(), in.color.end(), light.color);
        light.intensity = in.intensity;
        light.range = in.range;
        light.inner_cone_angle = in.spot.innerConeAngle;
        light.outer_cone_angle = in.spot.outerConeAngle;
        light.classic = classic_flag_of(in.extras);
        table.lights.push_back(light);
    }
    return table;
}

// A validated window onto an accessor's bytes.
struct AccessorData {
    const uint8_t* base = nullptr;
    size_t stride = 0;
    size_t count = 0;
    int component_type = 0;
    int type = 0;
    bool normalized = false;
};

// A node waiting to be visited. Its parent's world transform is shared by
// index (parent_worlds in traverse): a node with a million children, or a
// scene with a million roots, waits as a million small entries.
struct Traversal {
    int node = 0;
    uint32_t parent_world = 0;
    uint64_t path_hash = 0;
};

class Loader {
public:
    // `path` names the file in messages and in Scene::source.
    Loader(const std::filesystem::path& path, std::vector<std::string>& warnings,
           const GltfLoadOptions& options)
        : path_(path), warnings_(warnings), options_(options) {}

    Result<Scene> load_file();
    // `resource_folder` stands for the scene's folder (gltf_loader.h).
    Result<Scene> load(std::span<const uint8_t> bytes, const std::filesystem::path& resource_folder);

private:
    Error fail(const std::string& message) const { return Error{path_.string() + ": " + message}; }
    void warn(const std::string& message) { warnings_.push_back(path_.string() + ": " + message); }

    Result<MappedFile> map_file() const;
    // `on_consumed`: the node reader will not read the bytes before an offset again.
    Status parse(std::span<const uint8_t> bytes, const std::filesystem::path& resource_folder,
                 const ConsumedBytes& on_consumed = {});
    // tinygltf over `bytes` into model_; its warnings are added to `warnings`.
    Status parse_with_tinygltf(std::span<const uint8_t> bytes,
                               const std::filesystem::path& resource_folder,
                               std::vector<std::string>& warnings);
    // The rest of the load, once the file's bytes are parsed.
    Result<Scene> build_scene();
    Status validate_node_graph();
    Result<std::vector<int>> scene_roots();
    Status convert_materials();
    Status read_alpha(const tg::Material& in, const std::string& what, Material& out);
    Status read_normal_texture(const tg::Material& in, const std::string& what, Material& out);
    Status read_texture_coordinates(const tg::Material& in, const std::string& what, Material& out);
    Result<TextureCoordinates> coordinates_of(int tex_coord, const tg::ExtensionMap& extensions,
                                              const std::string& what);
    Status read_uvs(const tg::Primitive& prim, const std::string& what, Mesh& mesh);
    Status read_colors(const tg::Primitive& prim, const std::string& what, Mesh& mesh);
    Status read_tangents(const tg::Primitive& prim, const std::string& what, const glm::dmat3& linear,
                         Mesh& mesh) const;
    Result<std::vector<glm::vec4>> read_vec4(int index, const std::string& what) const;
    // `srgb`: colour data (base colour, emissive) rather than linear data
    // (metallic-roughness); an image used both ways becomes two textures.
    Result<int> texture_for(const tg::TextureInfo& info, const std::string& what,
                            bool srgb = true);
    Status traverse(const std::vector<int>& roots);
    Result<glm::dmat4> local_transform(int node_index) const;
    Status add_mesh(int node_index, int mesh_index, const glm::dmat4& world);
    Status add_primitive(int mesh_index, int primitive_index, const glm::dmat4& world);
    Result<std::vector<uint32_t>> read_triangles(const tg::Primitive& prim, int mode, const std::string& what,
                                                 size_t vertex_count) const;
    Status place_positions(const std::vector<glm::vec3>& positions, const glm::dmat4& world,
                           const std::string& what, Mesh& mesh) const;
    Status read_normals(const tg::Primitive& prim, const std::string& what, const glm::dmat3& linear,
                        Mesh& mesh) const;
    Status add_light(int node_index, const glm::dmat4& world, uint64_t path_hash);
    Result<int> light_index_of(const GltfNode& node, const std::string& node_what) const;
    Status read_light_emission(const GltfPunctualLight& in, const std::string& what, SceneLight& light) const;
    Status read_spot_cone(const GltfPunctualLight& in, const std::string& what, SceneLight& light) const;
    Status place_light(const glm::dmat4& world, const std::string& node_what, const std::string& what,
                       SceneLight& light) const;
    void add_camera(int node_index, int camera_index, const glm::dmat4& world);
    Status check_unique_light_guids() const;
    Status read_environment();
    void finish_cameras();

    // `expected` names the accepted types for the message; `accepts` checks them
    // before any range check, so a wrong type is reported as such.
    Result<AccessorData> view_accessor(int index, const std::string& what, const char* expected,
                                       bool (*accepts)(const tg::Accessor&)) const;
    Result<std::vector<glm::vec3>> read_vec3(int index, const std::string& what) const;
    Result<std::vector<glm::vec2>> read_uv(int index, const std::string& what) const;
    Result<std::vector<uint32_t>> read_indices(int index, const std::string& what,
                                               size_t vertex_count) const;

    std::filesystem::path path_;
    std::vector<std::string>& warnings_;
    GltfLoadOptions options_;
    std::filesystem::path resource_folder_;  // as parse() was given it
    tg::Model model_;
    // Nodes, scenes and punctual lights: read by gltf_node_reader, or taken
    // from model_ (whose copies are then dropped).
    GltfNodeTable nodes_;
    Scene scene_;
    std::map<std::pair<int, bool>, int> image_to_texture_;  // (glTF image, sRGB) -> Scene::textures
    std::vector<glm::dvec3> camera_forward_;  // per Scene::cameras entry, for finish_cameras()
};

Result<MappedFile> Loader::map_file() const {
    std::error_code ec;
    if (!std::filesystem::exists(path_, ec)) return fail("file does not exist");
    if (!std::filesystem::is_regular_file(path_, ec)) return fail("not a regular file");
    Result<MappedFile> file = MappedFile::open(path_);
    if (!file) return fail(file.error());
    return file;
}

Status Loader::parse(std::span<const uint8_t> bytes, const std::filesystem::path& resource_folder,
                     const ConsumedBytes& on_consumed) {
    resource_folder_ = resource_folder;
    if (bytes.empty()) return fail("the file is empty");
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) {
        return fail("the file is larger than 4 GiB");
    }
    if (options_.stream_nodes) {
        std::optional<GltfNodeSplit> split = read_gltf_nodes(bytes, on_consumed);
        if (split) {
            std::vector<std::string> warnings;
            const auto* remainder = reinterpret_cast<const uint8_t*>(split->remainder.data());
            if (parse_with_tinygltf({remainder, split->remainder.size()}, resource_folder,
                                    warnings)) {
                nodes_ = std::move(split->table);
                warnings_.insert(warnings_.end(), warnings.begin(), warnings.end());
                return Ok{};
            }
            // The whole file through tinygltf gives the message it always gave.
            model_ = tg::Model{};
        }
    }
    LC_RETURN_IF_ERROR(parse_with_tinygltf(bytes, resource_folder, warnings_));
    nodes_ = node_table_from(model_);
    // New vectors, not `= {}`: that clears and keeps a million nodes' capacity.
    model_.nodes = std::vector<tg::Node>();
    model_.lights = std::vector<tg::Light>();
    model_.scenes = std::vector<tg::Scene>();
    return Ok{};
}

Status Loader::parse_with_tinygltf(std::span<const uint8_t> bytes,
                                   const std::filesystem::path& resource_folder,
                                   std::vector<std::string>& warnings) {
    const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
    const auto length = static_cast<unsigned int>(bytes.size());
    tg::TinyGLTF gltf;
    ImageLoadContext image_context{&model_};
    gltf.SetImageLoader(&load_image_checked, &image_context);
    GltfResourceAccess access(resource_folder, options_.allow_external_resources);
    access.expect_buffer_sizes(external_buffer_sizes(bytes));
    gltf.SetFsCallbacks(access.callbacks());
    const std::string base_dir = resource_folder.string();
    std::string err;
    std::string warn_text;
    bool ok = false;
    try {
        ok = binary ? gltf.LoadBinaryFromMemory(&model_, &err, &warn_text, bytes.data(), length,
                                                base_dir)
                    : gltf.LoadASCIIFromString(&model_, &err, &warn_text,
                                               reinterpret_cast<const char*>(bytes.data()), length,
                                               base_dir);
    } catch (const std::exception& e) {
        // tinygltf throws on some malformed inputs (e.g. .at() on an empty chunk).
        return fail(std::string("malformed glTF: ") + e.what());
    }
    for (const std::string& line : split_lines(warn_text)) warnings.push_back(path_.string() + ": " + line);
    if (!ok) {
        std::string message = shorten_data_uris(trim(err));
        if (message.empty()) message = "tinygltf rejected the file without a message";
        if (message.find("Failed to decode 'uri'") != std::string::npos) {
            message += " (corrupt base64, or not as long as the buffer's byteLength)";
        }
        for (const std::string& refusal : access.refusals()) message += "; refused: " + refusal;
        return fail(std::string(binary ? "invalid glTF binary: " : "invalid glTF: ") + message);
    }
    // Refused images are dropped with tinygltf's warning; say why.
    for (const std::string& refusal : access.refusals()) {
        warnings.push_back(path_.string() + ": refused: " + refusal);
    }
    return Ok{};
}

// glTF requires the node hierarchy to be disjoint strict trees. We check it on
// every node (not only those a scene reaches) without recursion: at most one
// parent each, then no node may be its own ancestor.
Status Loader::validate_node_graph() {
    const int n = static_cast<int>(nodes_.nodes.size());
    std::vector<int> parent(size_t(n), -1);
    for (int i = 0; i < n; ++i) {
        for (int child : nodes_.children_of(nodes_.nodes[size_t(i)])) {
            if (child < 0 || child >= n) {
                return fail("node " + std::to_string(i) + " lists child " + std::to_string(child) +
                            ", which does not exist (the file has " + std::to_string(n) +
                            " nodes)");
            }
            if (child == i) {
                return fail("recursive node graph: node " + std::to_string(i) +
                            " is its own child");
            }
            if (parent[size_t(child)] != -1) {
                return fail("node " + std::to_string(child) + " has two parents (nodes " +
                            std::to_string(parent[size_t(child)]) + " and " + std::to_string(i) +
                            "); glTF node hierarchies must be trees");
            }
            parent[size_t(child)] = i;
        }
    }
    // 0: not yet seen, 1: on the current upward walk, 2: known to reach a root.
    std::vector<uint8_t> state(size_t(n), 0);
    std::vector<int> walk;
    for (int start = 0; start < n; ++start) {
        walk.clear();
        int j = start;
        while (j != -1 && state[size_t(j)] == 0) {
            state[size_t(j)] = 1;
            walk.push_back(j);
            j = parent[size_t(j)];
        }
        if (j != -1 && state[size_t(j)] == 1) {
            return fail("recursive node graph: node " + std::to_string(j) + " is its own ancestor");
        }
        for (int k : walk) state[size_t(k)] = 2;
    }
    return Ok{};
}

Result<std::vector<int>> Loader::scene_roots() {
    const int scene_count = static_cast<int>(nodes_.scenes.size());
    const int node_count = static_cast<int>(nodes_.nodes.size());
    if (model_.defaultScene >= scene_count) {
        return fail("'scene' is " + std::to_string(model_.defaultScene) + " but the file has " +
                    std::to_string(scene_count) + " scenes");
    }
    if (scene_count == 0) {
        // No scene: draw every root node (the spec leaves this to the application).
        std::vector<bool> is_child(size_t(node_count), false);
        for (const GltfNode& node : nodes_.nodes)
            for (int child : nodes_.children_of(node)) is_child[size_t(child)] = true;
        std::vector<int> roots;
        for (int i = 0; i < node_count; ++i)
            if (!is_child[size_t(i)]) roots.push_back(i);
        if (node_count > 0) warn("the file has no scene; using every root node");
        return roots;
    }
    const int chosen = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    const std::span<const int32_t> listed = nodes_.roots_of(size_t(chosen));
    std::vector<int> roots(listed.begin(), listed.end());
    for (int root : roots) {
        if (root < 0 || root >= node_count) {
            return fail("scene " + std::to_string(chosen) + " lists node " + std::to_string(root) +
                        ", which does not exist (the file has " + std::to_string(node_count) +
                        " nodes)");
        }
    }
    return roots;
}

Result<int> Loader::texture_for(const tg::TextureInfo& info, const std::string& what, bool srgb) {
    if (info.index < 0) return -1;
    if (info.index >= static_cast<int>(model_.textures.size())) {
        return fail(what + " uses texture " + std::to_string(info.index) +
                    ", which does not exist");
    }
    const tg::Texture& texture = model_.textures[size_t(info.index)];
    if (texture.source < 0) {
        warn(what + ": texture " + std::to_string(info.index) + " has no image; ignored");
        return -1;
    }
    if (texture.source >= static_cast<int>(model_.images.size())) {
        return fail("texture " + std::to_string(info.index) + " uses image " +
                    std::to_string(texture.source) + ", which does not exist");
    }
    const std::pair<int, bool> key{texture.source, srgb};
    auto found = image_to_texture_.find(key);
    if (found != image_to_texture_.end()) return found->second;

    const tg::Image& image = model_.images[size_t(texture.source)];
    const int bytes_per_channel = image.bits == 16 ? 2 : (image.bits == 8 ? 1 : 0);
    const size_t expected = size_t(std::max(image.width, 0)) * size_t(std::max(image.height, 0)) *
                            size_t(std::max(image.component, 0)) * size_t(bytes_per_channel);
    if (image.image.empty() || image.width <= 0 || image.height <= 0 || image.component < 1 ||
        image.component > 4 || bytes_per_channel == 0 || image.image.size() != expected) {
        warn(what + ": image " + std::to_string(texture.source) +
             " has no usable pixels; the texture is ignored");
        image_to_texture_[key] = -1;
        return -1;
    }
    Texture out;
    out.srgb = srgb;
    out.width = image.width;
    out.height = image.height;
    out.rgba8.resize(size_t(image.width) * size_t(image.height) * 4);
    const size_t pixels = size_t(image.width) * size_t(image.height);
    for (size_t p = 0; p < pixels; ++p) {
        uint8_t rgba[4] = {0, 0, 0, 255};
        for (int c = 0; c < image.component; ++c) {
            // 16-bit channels keep their high byte (little-endian storage).
            const size_t at = (p * size_t(image.component) + size_t(c)) * size_t(bytes_per_channel);
            rgba[c] = bytes_per_channel == 2 ? image.image[at + 1] : image.image[at];
        }
        if (image.component == 1 || image.component == 2) {
            // Grey (+ alpha): replicate the grey channel.
            const uint8_t alpha = image.component == 2 ? rgba[1] : 255;
            rgba[1] = rgba[0];
            rgba[2] = rgba[0];
            rgba[3] = alpha;
        }
        std::memcpy(&out.rgba8[p * 4], rgba, 4);
    }
    const int index = static_cast<int>(scene_.textures.size());
    scene_.textures.push_back(std::move(out));
    image_to_texture_[key] = index;
    return index;
}

// normalTexture (linear data) and its scale.
Status Loader::read_normal_texture(const tg::Material& in, const std::string& what, Material& out) {
    tg::TextureInfo info;
    info.index = in.normalTexture.index;
    info.texCoord = in.normalTexture.texCoord;
    Result<int> texture = texture_for(info, what + " normalTexture", /*srgb=*/false);
    if (!texture) return Error{texture.error()};
    if (!finite(in.normalTexture.scale)) return fail(what + ": normalTexture.scale must be finite");
    out.normal_texture = *texture;
    out.normal_scale = float(in.normalTexture.scale);
    return Ok{};
}

// One texture's set and KHR_texture_transform.
Result<TextureCoordinates> Loader::coordinates_of(int tex_coord, const tg::ExtensionMap& extensions,
                                                  const std::string& what) {
    TextureCoordinates out;
    out.set = tex_coord;
    auto ext = extensions.find("KHR_texture_transform");
    if (ext != extensions.end() && ext->second.IsObject()) {
        const tg::Value& t = ext->second;
        out.transformed = true;
        auto pair = [&](const char* key, glm::vec2& into) {
            const tg::Value& v = t.Get(key);
            if (v.IsArray() && v.ArrayLen() == 2 && v.Get(0).IsNumber() && v.Get(1).IsNumber())
                into = glm::vec2(float(v.Get(0).GetNumberAsDouble()), float(v.Get(1).GetNumberAsDouble()));
        };
        pair("offset", out.offset);
        pair("scale", out.scale);
        if (t.Get("rotation").IsNumber()) out.rotation = float(t.Get("rotation").GetNumberAsDouble());
        if (t.Get("texCoord").IsInt()) out.set = t.Get("texCoord").GetNumberAsInt();
        if (!std::isfinite(out.offset.x) || !std::isfinite(out.offset.y) || !std::isfinite(out.scale.x) ||
            !std::isfinite(out.scale.y) || !std::isfinite(out.rotation))
            return fail(what + ": KHR_texture_transform must hold finite numbers");
    }
    if (out.set < 0 || out.set > 1) {
        warn(what + " uses TEXCOORD_" + std::to_string(out.set) +
             "; only TEXCOORD_0 and TEXCOORD_1 are read, so it is sampled with TEXCOORD_0");
        out.set = 0;
    }
    return out;
}

// The coordinates of the material's first texture (base colour, normal,
// emissive, metallic-roughness); another texture asking for others is
// sampled with these, with a warning.
Status Loader::read_texture_coordinates(const tg::Material& in, const std::string& what, Material& out) {
    const tg::PbrMetallicRoughness& pbr = in.pbrMetallicRoughness;
    struct Use {
        const char* name;
        int index;
        int tex_coord;
        const tg::ExtensionMap* extensions;
    };
    const Use uses[] = {
        {"baseColorTexture", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord,
         &pbr.baseColorTexture.extensions},
        {"normalTexture", in.normalTexture.index, in.normalTexture.texCoord, &in.normalTexture.extensions},
        {"emissiveTexture", in.emissiveTexture.index, in.emissiveTexture.texCoord,
         &in.emissiveTexture.extensions},
        {"metallicRoughnessTexture", pbr.metallicRoughnessTexture.index,
         pbr.metallicRoughnessTexture.texCoord, &pbr.metallicRoughnessTexture.extensions}};
    bool chosen = false;
    for (const Use& use : uses) {
        if (use.index < 0) continue;
        Result<TextureCoordinates> c = coordinates_of(use.tex_coord, *use.extensions, what + " " + use.name);
        if (!c) return Error{c.error()};
        const TextureCoordinates& mine = *c;
        const TextureCoordinates& first = out.texture_coordinates;
        if (!chosen) {
            out.texture_coordinates = mine;
            chosen = true;
        } else if (mine.set != first.set || mine.transformed != first.transformed ||
                   mine.offset != first.offset || mine.scale != first.scale ||
                   mine.rotation != first.rotation) {
            warn(what + " " + use.name +
                 " asks for other texture coordinates than the material's "
                 "first texture; it is sampled with those");
        }
    }
    return Ok{};
}

// alphaMode, alphaCutoff and doubleSided; an unknown mode is drawn opaque.
Status Loader::read_alpha(const tg::Material& in, const std::string& what, Material& out) {
    if (in.alphaMode == "MASK") {
        out.alpha_mode = AlphaMode::kMask;
    } else if (in.alphaMode == "BLEND") {
        out.alpha_mode = AlphaMode::kBlend;
    } else if (!in.alphaMode.empty() && in.alphaMode != "OPAQUE") {
        warn(what + ": alphaMode '" + in.alphaMode + "' is not OPAQUE, MASK or BLEND; drawn opaque");
    }
    if (!finite(in.alphaCutoff) || in.alphaCutoff < 0.0)
        return fail(what + ": alphaCutoff must be finite and >= 0");
    out.alpha_cutoff = float(in.alphaCutoff);
    out.double_sided = in.doubleSided;
    return Ok{};
}

Status Loader::convert_materials() {
    for (size_t i = 0; i < model_.materials.size(); ++i) {
        const tg::Material& in = model_.materials[i];
        const std::string what = "material " + std::to_string(i);
        Material out;
        const std::vector<double>& base = in.pbrMetallicRoughness.baseColorFactor;
        if (base.size() != 4 || !all_finite(base)) {
            return fail(what + ": baseColorFactor must be 4 finite numbers");
        }
        out.base_color_factor =
            glm::vec4(float(base[0]), float(base[1]), float(base[2]), float(base[3]));
        const double metallic = in.pbrMetallicRoughness.metallicFactor;
        const double roughness = in.pbrMetallicRoughness.roughnessFactor;
        if (!finite(metallic) || !finite(roughness)) {
            return fail(what + ": metallicFactor and roughnessFactor must be finite");
        }
        out.metallic = float(std::clamp(metallic, 0.0, 1.0));
        out.roughness = float(std::clamp(roughness, 0.0, 1.0));
        if (in.emissiveFactor.size() != 3 || !all_finite(in.emissiveFactor)) {
            return fail(what + ": emissiveFactor must be 3 finite numbers");
        }
        double strength = 1.0;
        auto ext = in.extensions.find(kEmissiveStrengthExtension);
        if (ext != in.extensions.end() && ext->second.IsObject() &&
            ext->second.Get("emissiveStrength").IsNumber()) {
            strength = ext->second.Get("emissiveStrength").GetNumberAsDouble();
            if (!finite(strength) || strength < 0.0) {
                return fail(what + ": emissiveStrength must be finite and >= 0");
            }
        }
        out.emissive_factor = glm::vec3(float(in.emissiveFactor[0] * strength),
                                        float(in.emissiveFactor[1] * strength),
                                        float(in.emissiveFactor[2] * strength));
        for (int c = 0; c < 4; ++c) {
            if (out.base_color_factor[c] < 0.0f) return fail(what + ": negative baseColorFactor");
        }
        for (int c = 0; c < 3; ++c) {
            if (out.emissive_factor[c] < 0.0f) return fail(what + ": negative emissiveFactor");
        }
        Result<int> base_texture =
            texture_for(in.pbrMetallicRoughness.baseColorTexture, what + " baseColorTexture");
        if (!base_texture) return Error{base_texture.error()};
        out.base_color_texture = *base_texture;
        Result<int> emissive_texture = texture_for(in.emissiveTexture, what + " emissiveTexture");
        if (!emissive_texture) return Error{emissive_texture.error()};
        out.emissive_texture = *emissive_texture;
        Result<int> metallic_roughness_texture =
            texture_for(in.pbrMetallicRoughness.metallicRoughnessTexture,
                        what + " metallicRoughnessTexture", /*srgb=*/false);
        if (!metallic_roughness_texture) return Error{metallic_roughness_texture.error()};
        out.metallic_roughness_texture = *metallic_roughness_texture;
        LC_RETURN_IF_ERROR(read_normal_texture(in, what, out));
        LC_RETURN_IF_ERROR(read_texture_coordinates(in, what, out));
        // Light passes through blended and transmissive surfaces (a lamp's
        // glass): they are drawn opaque but hide no light.
        double transmission = 0.0;
        auto glass = in.extensions.find("KHR_materials_transmission");
        if (glass != in.extensions.end() && glass->second.IsObject() &&
            glass->second.Get("transmissionFactor").IsNumber())
            transmission = glass->second.Get("transmissionFactor").GetNumberAsDouble();
        out.casts_shadows = in.alphaMode != "BLEND" && !(transmission > 0.0);
        LC_RETURN_IF_ERROR(read_alpha(in, what, out));
        scene_.materials.push_back(out);
    }
    return Ok{};
}

Result<glm::dmat4> Loader::local_transform(int node_index) const {
    const GltfNode& node = nodes_.nodes[size_t(node_index)];
    const std::span<const double> matrix = nodes_.values(node.matrix);
    const std::span<const double> translation = nodes_.values(node.translation);
    const std::span<const double> rotation = nodes_.values(node.rotation);
    const std::span<const double> scale = nodes_.values(node.scale);
    const std::string what = "node " + std::to_string(node_index);
    if (!matrix.empty()) {
        if (matrix.size() != 16) {
            return fail(what + ": 'matrix' has " + std::to_string(matrix.size()) +
                        " numbers, expected 16");
        }
        if (!all_finite(matrix)) return fail(what + ": 'matrix' has a non-finite value");
        return glm::make_mat4(matrix.data());  // both column-major
    }
    glm::dmat4 m(1.0);
    if (!translation.empty()) {
        if (translation.size() != 3) return fail(what + ": 'translation' needs 3 numbers");
        if (!all_finite(translation)) {
            return fail(what + ": 'translation' has a non-finite value");
        }
        m[3] = glm::dvec4(translation[0], translation[1], translation[2], 1.0);
    }
    if (!rotation.empty()) {
        if (rotation.size() != 4) return fail(what + ": 'rotation' needs 4 numbers");
        if (!all_finite(rotation)) return fail(what + ": 'rotation' has a non-finite value");
        // glTF stores x, y, z, w; glm's constructor takes w first.
        glm::dquat q(rotation[3], rotation[0], rotation[1], rotation[2]);
        const double len = glm::length(q);
        if (!(len > 1e-12)) return fail(what + ": 'rotation' is a zero quaternion");
        m = m * glm::mat4_cast(q / len);
    }
    if (!scale.empty()) {
        if (scale.size() != 3) return fail(what + ": 'scale' needs 3 numbers");
        if (!all_finite(scale)) return fail(what + ": 'scale' has a non-finite value");
        glm::dmat4 s(1.0);
        s[0][0] = scale[0];
        s[1][1] = scale[1];
        s[2][2] = scale[2];
        m = m * s;
    }
    return m;
}

Result<AccessorData> Loader::view_accessor(int index, const std::string& what, const char* expected,
                                           bool (*accepts)(const tg::Accessor&)) const {
    if (index < 0 || index >= static_cast<int>(model_.accessors.size())) {
        return fail(what + " uses accessor " + std::to_string(index) +
                    ", which does not exist (the file has " +
                    std::to_string(model_.accessors.size()) + " accessors)");
    }
    const tg::Accessor& acc = model_.accessors[size_t(index)];
    const std::string name = "accessor " + std::to_string(index) + " (" + what + ")";
    if (!accepts(acc)) {
        return fail(name + " is " + type_name(acc.type) + " " +
                    component_type_name(acc.componentType) + (acc.normalized ? " normalized" : "") +
                    ", expected " + expected);
    }
    if (acc.sparse.isSparse) return fail(name + " is sparse; sparse accessors are not supported");
    if (acc.bufferView < 0 || acc.bufferView >= static_cast<int>(model_.bufferViews.size())) {
        return fail(name + " has bufferView " + std::to_string(acc.bufferView) +
                    ", which does not exist");
    }
    const tg::BufferView& view = model_.bufferViews[size_t(acc.bufferView)];
    if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size())) {
        return fail("bufferView " + std::to_string(acc.bufferView) + " has buffer " +
                    std::to_string(view.buffer) + ", which does not exist");
    }
    const tg::Buffer& buffer = model_.buffers[size_t(view.buffer)];
    if (!range_fits(view.byteOffset, view.byteLength, buffer.data.size())) {
        return fail("bufferView " + std::to_string(acc.bufferView) + " (offset " +
                    std::to_string(view.byteOffset) + ", length " +
                    std::to_string(view.byteLength) + ") lies outside buffer " +
                    std::to_string(view.buffer) + ", which has " +
                    std::to_string(buffer.data.size()) + " bytes");
    }
    const int csize = component_size(acc.componentType);
    const int ccount = component_count(acc.type);
    if (csize == 0 || ccount == 0) {
        return fail(name + " has an unknown type or component type");
    }
    const size_t element = size_t(csize) * size_t(ccount);
    const size_t stride = view.byteStride != 0 ? view.byteStride : element;
    if (stride < element) {
        return fail(name + ": byteStride " + std::to_string(stride) +
                    " is smaller than one element (" + std::to_string(element) + " bytes)");
    }
    if (acc.count > 0) {
        // The last element must end inside the buffer view.
        const size_t limit = view.byteLength;
        bool fits = acc.byteOffset <= limit && element <= limit - acc.byteOffset;
        if (fits) fits = (acc.count - 1) <= (limit - acc.byteOffset - element) / stride;
        if (!fits) {
            return fail(name + ": " + std::to_string(acc.count) + " elements at offset " +
                        std::to_string(acc.byteOffset) + " with stride " + std::to_string(stride) +
                        " do not fit in bufferView " + std::to_string(acc.bufferView) + " (" +
                        std::to_string(view.byteLength) + " bytes)");
        }
    }
    AccessorData data;
    data.base = buffer.data.data() + view.byteOffset + acc.byteOffset;
    data.stride = stride;
    data.count = acc.count;
    data.component_type = acc.componentType;
    data.type = acc.type;
    data.normalized = acc.normalized;
    return data;
}

bool is_vec3_float(const tg::Accessor& a) {
    return a.type == TINYGLTF_TYPE_VEC3 && a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
}

bool is_uv(const tg::Accessor& a) {
    const int ct = a.componentType;
    return a.type == TINYGLTF_TYPE_VEC2 &&
           (ct == TINYGLTF_COMPONENT_TYPE_FLOAT ||
            (a.normalized && (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                              ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)));
}

bool is_index(const tg::Accessor& a) {
    const int ct = a.componentType;
    return a.type == TINYGLTF_TYPE_SCALAR && (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                              ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
                                              ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
}

Result<std::vector<glm::vec3>> Loader::read_vec3(int index, const std::string& what) const {
    Result<AccessorData> data = view_accessor(index, what, "VEC3 FLOAT", &is_vec3_float);
    if (!data) return Error{data.error()};
    std::vector<glm::vec3> out(data->count);
    for (size_t i = 0; i < data->count; ++i) {
        float v[3];
        std::memcpy(v, data->base + i * data->stride, sizeof v);
        if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2])) {
            return fail("accessor " + std::to_string(index) + " (" + what +
                        ") has a non-finite value at element " + std::to_string(i));
        }
        out[i] = glm::vec3(v[0], v[1], v[2]);
    }
    return out;
}

Result<std::vector<glm::vec2>> Loader::read_uv(int index, const std::string& what) const {
    Result<AccessorData> data =
        view_accessor(index, what, "VEC2 FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT", &is_uv);
    if (!data) return Error{data.error()};
    const int ct = data->component_type;
    const bool float_uv = ct == TINYGLTF_COMPONENT_TYPE_FLOAT;
    std::vector<glm::vec2> out(data->count);
    for (size_t i = 0; i < data->count; ++i) {
        const uint8_t* p = data->base + i * data->stride;
        float uv[2];
        if (float_uv) {
            std::memcpy(uv, p, sizeof uv);
            if (!std::isfinite(uv[0]) || !std::isfinite(uv[1])) {
                return fail("accessor " + std::to_string(index) + " (" + what +
                            ") has a non-finite value at element " + std::to_string(i));
            }
        } else if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
            uv[0] = float(p[0]) / 255.0f;
            uv[1] = float(p[1]) / 255.0f;
        } else {
            uint16_t s[2];
            std::memcpy(s, p, sizeof s);
            uv[0] = float(s[0]) / 65535.0f;
            uv[1] = float(s[1]) / 65535.0f;
        }
        out[i] = glm::vec2(uv[0], uv[1]);
    }
    return out;
}

Result<std::vector<uint32_t>> Loader::read_indices(int index, const std::string& what,
                                                   size_t vertex_count) const {
    Result<AccessorData> data =
        view_accessor(index, what, "SCALAR UNSIGNED_BYTE/UNSIGNED_SHORT/UNSIGNED_INT", &is_index);
    if (!data) return Error{data.error()};
    const int ct = data->component_type;
    std::vector<uint32_t> out(data->count);
    for (size_t i = 0; i < data->count; ++i) {
        const uint8_t* p = data->base + i * data->stride;
        uint32_t v = 0;
        if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
            v = p[0];
        } else if (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
            uint16_t s;
            std::memcpy(&s, p, sizeof s);
            v = s;
        } else {
            std::memcpy(&v, p, sizeof v);
        }
        if (v >= vertex_count) {
            return fail("accessor " + std::to_string(index) + " (" + what + "): index " +
                        std::to_string(v) + " at element " + std::to_string(i) +
                        " is out of range of the " + std::to_string(vertex_count) + " vertices");
        }
        out[i] = v;
    }
    return out;
}

// Area-weighted vertex normals: each triangle adds its unnormalised cross
// product (twice its area) to its three vertices.
std::vector<glm::vec3> generate_normals(const std::vector<glm::vec3>& positions,
                                        const std::vector<uint32_t>& indices) {
    std::vector<glm::dvec3> sum(positions.size(), glm::dvec3(0.0));
    for (size_t t = 0; t + 2 < indices.size(); t += 3) {
        const glm::dvec3 a(positions[indices[t]]);
        const glm::dvec3 b(positions[indices[t + 1]]);
        const glm::dvec3 c(positions[indices[t + 2]]);
        const glm::dvec3 n = glm::cross(b - a, c - a);
        for (int k = 0; k < 3; ++k) sum[indices[t + size_t(k)]] += n;
    }
    std::vector<glm::vec3> normals(positions.size());
    for (size_t i = 0; i < sum.size(); ++i) {
        const double len = glm::length(sum[i]);
        // A vertex of degenerate triangles only has no normal; any unit vector will do.
        normals[i] =
            len > 0.0 && std::isfinite(len) ? glm::vec3(sum[i] / len) : glm::vec3(0.0f, 1.0f, 0.0f);
    }
    return normals;
}

// Strips and fans become triangle lists with the winding glTF prescribes.
std::vector<uint32_t> triangle_list(const std::vector<uint32_t>& indices, int mode) {
    std::vector<uint32_t> list;
    for (size_t i = 2; i < indices.size(); ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
            list.insert(list.end(), {indices[0], indices[i - 1], indices[i]});
        } else if (i % 2 == 0) {
            list.insert(list.end(), {indices[i - 2], indices[i - 1], indices[i]});
        } else {
            list.insert(list.end(), {indices[i - 1], indices[i - 2], indices[i]});
        }
    }
    return list;
}

Status Loader::add_primitive(int mesh_index, int primitive_index, const glm::dmat4& world) {
    const tg::Primitive& prim =
        model_.meshes[size_t(mesh_index)].primitives[size_t(primitive_index)];
    const std::string what =
        "mesh " + std::to_string(mesh_index) + " primitive " + std::to_string(primitive_index);
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        warn(what + " has mode " + std::to_string(mode) +
             " (points or lines); only triangles are drawn, so it is skipped");
        return Ok{};
    }
    auto position_it = prim.attributes.find("POSITION");
    if (position_it == prim.attributes.end()) {
        warn(what + " has no POSITION attribute; skipped");
        return Ok{};
    }
    if (prim.material < -1 || prim.material >= static_cast<int>(model_.materials.size())) {
        return fail(what + " uses material " + std::to_string(prim.material) +
                    ", which does not exist");
    }
    Result<std::vector<glm::vec3>> positions = read_vec3(position_it->second, what + " POSITION");
    if (!positions) return Error{positions.error()};
    Result<std::vector<uint32_t>> indices = read_triangles(prim, mode, what, positions->size());
    if (!indices) return Error{indices.error()};

    Mesh mesh;
    mesh.material = prim.material;
    LC_RETURN_IF_ERROR(place_positions(*positions, world, what, mesh));
    // A mirroring transform flips the winding; swap two corners to keep
    // front faces front-facing.
    const glm::dmat3 linear(world);
    const double det = glm::determinant(linear);
    if (det < 0.0) {
        for (size_t t = 0; t + 2 < indices->size(); t += 3) std::swap((*indices)[t + 1], (*indices)[t + 2]);
    }
    mesh.indices = std::move(*indices);
    LC_RETURN_IF_ERROR(read_normals(prim, what, linear, mesh));
    LC_RETURN_IF_ERROR(read_uvs(prim, what, mesh));
    LC_RETURN_IF_ERROR(read_colors(prim, what, mesh));
    LC_RETURN_IF_ERROR(read_tangents(prim, what, linear, mesh));
    if (!mesh.indices.empty()) scene_.meshes.push_back(std::move(mesh));
    return Ok{};
}

// The primitive's triangles as a list: its indices, or its vertices in order.
Result<std::vector<uint32_t>> Loader::read_triangles(const tg::Primitive& prim, int mode, const std::string& what,
                                                     size_t vertex_count) const {
    std::vector<uint32_t> indices;
    if (prim.indices >= 0) {
        Result<std::vector<uint32_t>> read = read_indices(prim.indices, what + " indices", vertex_count);
        if (!read) return Error{read.error()};
        indices = std::move(*read);
    } else {
        if (vertex_count > std::numeric_limits<uint32_t>::max()) {
            return fail(what + " has too many vertices");
        }
        indices.resize(vertex_count);
        for (size_t i = 0; i < vertex_count; ++i) indices[i] = uint32_t(i);
    }
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP || mode == TINYGLTF_MODE_TRIANGLE_FAN) {
        return triangle_list(indices, mode);
    }
    if (indices.size() % 3 != 0) {
        return fail(what + " has " + std::to_string(indices.size()) +
                    " indices, which is not a multiple of 3");
    }
    return indices;
}

// The positions in world space, each finite.
Status Loader::place_positions(const std::vector<glm::vec3>& positions, const glm::dmat4& world,
                               const std::string& what, Mesh& mesh) const {
    mesh.positions.resize(positions.size());
    for (size_t i = 0; i < positions.size(); ++i) {
        const glm::dvec4 p = world * glm::dvec4(glm::dvec3(positions[i]), 1.0);
        const glm::vec3 pf(p);
        if (!std::isfinite(pf.x) || !std::isfinite(pf.y) || !std::isfinite(pf.z)) {
            return fail(what + ": vertex " + std::to_string(i) + " is not finite after the node transform");
        }
        mesh.positions[i] = pf;
    }
    return Ok{};
}

// NORMAL through the inverse transpose, or generated from the triangles where
// the file has none, a normal is degenerate or the transform is singular.
Status Loader::read_normals(const tg::Primitive& prim, const std::string& what, const glm::dmat3& linear,
                            Mesh& mesh) const {
    const size_t vertex_count = mesh.positions.size();
    auto normal_it = prim.attributes.find("NORMAL");
    const double det = glm::determinant(linear);
    const bool invertible = std::abs(det) > 1e-300 && std::isfinite(det);
    if (normal_it == prim.attributes.end() || !invertible) {
        mesh.normals = generate_normals(mesh.positions, mesh.indices);
        return Ok{};
    }
    Result<std::vector<glm::vec3>> normals = read_vec3(normal_it->second, what + " NORMAL");
    if (!normals) return Error{normals.error()};
    if (normals->size() != vertex_count) {
        return fail(what + ": NORMAL has " + std::to_string(normals->size()) +
                    " elements but POSITION has " + std::to_string(vertex_count));
    }
    const glm::dmat3 normal_matrix = glm::transpose(glm::inverse(linear));
    std::vector<glm::vec3> generated;  // only computed if some normal is degenerate
    mesh.normals.resize(vertex_count);
    for (size_t i = 0; i < vertex_count; ++i) {
        const glm::dvec3 n = normal_matrix * glm::dvec3((*normals)[i]);
        const double len = glm::length(n);
        if (len > 1e-20 && std::isfinite(len)) {
            mesh.normals[i] = glm::vec3(n / len);
        } else {
            if (generated.empty()) generated = generate_normals(mesh.positions, mesh.indices);
            mesh.normals[i] = generated[i];
        }
    }
    return Ok{};
}

// The set the material's textures use (TEXCOORD_0 where the asked-for one is
// missing), through its KHR_texture_transform.
Status Loader::read_uvs(const tg::Primitive& prim, const std::string& what, Mesh& mesh) {
    TextureCoordinates coordinates;
    if (prim.material >= 0 && size_t(prim.material) < scene_.materials.size())
        coordinates = scene_.materials[size_t(prim.material)].texture_coordinates;
    std::string name = "TEXCOORD_" + std::to_string(coordinates.set);
    auto uv_it = prim.attributes.find(name);
    if (uv_it == prim.attributes.end() && coordinates.set != 0) {
        warn(what + " has no " + name + " for its material's textures; TEXCOORD_0 is used");
        name = "TEXCOORD_0";
        uv_it = prim.attributes.find(name);
    }
    if (uv_it == prim.attributes.end()) return Ok{};
    Result<std::vector<glm::vec2>> uvs = read_uv(uv_it->second, what + " " + name);
    if (!uvs) return Error{uvs.error()};
    if (uvs->size() != mesh.positions.size()) {
        return fail(what + ": " + name + " has " + std::to_string(uvs->size()) +
                    " elements but POSITION has " + std::to_string(mesh.positions.size()));
    }
    mesh.uvs = std::move(*uvs);
    if (coordinates.transformed)
        for (glm::vec2& uv : mesh.uvs) uv = transform_uv(coordinates, uv);
    return Ok{};
}

bool is_color(const tg::Accessor& a) {
    const int ct = a.componentType;
    return (a.type == TINYGLTF_TYPE_VEC3 || a.type == TINYGLTF_TYPE_VEC4) &&
           (ct == TINYGLTF_COMPONENT_TYPE_FLOAT ||
            (a.normalized &&
             (ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || ct == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT)));
}

// COLOR_0: VEC3 or VEC4, float or normalized unsigned; alpha 1 for VEC3.
Status Loader::read_colors(const tg::Primitive& prim, const std::string& what, Mesh& mesh) {
    auto it = prim.attributes.find("COLOR_0");
    if (it == prim.attributes.end()) return Ok{};
    Result<AccessorData> data =
        view_accessor(it->second, what + " COLOR_0",
                      "VEC3/VEC4 FLOAT or normalized UNSIGNED_BYTE/UNSIGNED_SHORT", &is_color);
    if (!data) return Error{data.error()};
    if (data->count != mesh.positions.size())
        return fail(what + ": COLOR_0 has " + std::to_string(data->count) + " elements but POSITION has " +
                    std::to_string(mesh.positions.size()));
    const int components = data->type == TINYGLTF_TYPE_VEC4 ? 4 : 3;
    mesh.colors.assign(data->count, glm::vec4(1.0f));
    for (size_t i = 0; i < data->count; ++i) {
        const uint8_t* p = data->base + i * data->stride;
        for (int c = 0; c < components; ++c) {
            float v = 0.0f;
            if (data->component_type == TINYGLTF_COMPONENT_TYPE_FLOAT) {
                std::memcpy(&v, p + 4 * c, sizeof v);
            } else if (data->component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE) {
                v = float(p[c]) / 255.0f;
            } else {
                uint16_t u;
                std::memcpy(&u, p + 2 * c, sizeof u);
                v = float(u) / 65535.0f;
            }
            if (!std::isfinite(v))
                return fail(what + ": COLOR_0 has a non-finite value at element " + std::to_string(i));
            mesh.colors[i][c] = std::clamp(v, 0.0f, 1.0f);
        }
    }
    return Ok{};
}

// Tangents only for a material with a normal map: the file's TANGENT through
// the node's transform (a mirroring one flips the bitangent's sign), else
// generated (tangent_frames.h).
Status Loader::read_tangents(const tg::Primitive& prim, const std::string& what, const glm::dmat3& linear,
                             Mesh& mesh) const {
    const bool normal_mapped = prim.material >= 0 && size_t(prim.material) < scene_.materials.size() &&
                               scene_.materials[size_t(prim.material)].normal_texture >= 0;
    if (!normal_mapped || mesh.uvs.empty()) return Ok{};
    auto it = prim.attributes.find("TANGENT");
    if (it == prim.attributes.end()) {
        mesh.tangents = generate_tangents(mesh.positions, mesh.normals, mesh.uvs, mesh.indices);
        return Ok{};
    }
    Result<std::vector<glm::vec4>> tangents = read_vec4(it->second, what + " TANGENT");
    if (!tangents) return Error{tangents.error()};
    if (tangents->size() != mesh.positions.size())
        return fail(what + ": TANGENT has " + std::to_string(tangents->size()) +
                    " elements but POSITION has " + std::to_string(mesh.positions.size()));
    const float mirror = glm::determinant(linear) < 0.0 ? -1.0f : 1.0f;
    mesh.tangents.resize(tangents->size());
    for (size_t i = 0; i < tangents->size(); ++i) {
        const glm::dvec3 t = linear * glm::dvec3((*tangents)[i]);
        const double length = glm::length(t);
        const float sign = (*tangents)[i].w < 0.0f ? -mirror : mirror;
        mesh.tangents[i] = length > 1e-20 && std::isfinite(length)
                               ? glm::vec4(glm::vec3(t / length), sign)
                               : glm::vec4(any_orthogonal(mesh.normals[i]), sign);
    }
    return Ok{};
}

bool is_vec4_float(const tg::Accessor& a) {
    return a.type == TINYGLTF_TYPE_VEC4 && a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
}

Result<std::vector<glm::vec4>> Loader::read_vec4(int index, const std::string& what) const {
    Result<AccessorData> data = view_accessor(index, what, "VEC4 FLOAT", &is_vec4_float);
    if (!data) return Error{data.error()};
    std::vector<glm::vec4> out(data->count);
    for (size_t i = 0; i < data->count; ++i) {
        float v[4];
        std::memcpy(v, data->base + i * data->stride, sizeof v);
        for (float c : v)
            if (!std::isfinite(c))
                return fail("accessor " + std::to_string(index) + " (" + what +
                            ") has a non-finite value at element " + std::to_string(i));
        out[i] = glm::vec4(v[0], v[1], v[2], v[3]);
    }
    return out;
}

Status Loader::add_mesh(int node_index, int mesh_index, const glm::dmat4& world) {
    if (mesh_index >= static_cast<int>(model_.meshes.size())) {
        return fail("node " + std::to_string(node_index) + " uses mesh " +
                    std::to_string(mesh_index) + ", which does not exist");
    }
    const tg::Mesh& mesh = model_.meshes[size_t(mesh_index)];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
        Status status = add_primitive(mesh_index, static_cast<int>(p), world);
        if (!status) return status;
    }
    return Ok{};
}

// An `extras.<key>` flag; other types than boolean are ignored with a warning.
bool extras_flag(ExtrasFlag flag, const char* key, const std::string& what,
                 std::vector<std::string>& warnings, const std::string& file) {
    if (flag == ExtrasFlag::kNotBoolean) {
        warnings.push_back(file + ": " + what + ": extras." + key + " is not a boolean; ignored");
    }
    return flag == ExtrasFlag::kTrue;
}

Status Loader::add_light(int node_index, const glm::dmat4& world, uint64_t path_hash) {
    const std::string node_what = "node " + std::to_string(node_index);
    const GltfNode& node = nodes_.nodes[size_t(node_index)];
    Result<int> light_index = light_index_of(node, node_what);
    if (!light_index) return Error{light_index.error()};
    const GltfPunctualLight& in = nodes_.lights[size_t(*light_index)];
    const std::string_view name = nodes_.string(in.name);
    const std::string what = "light " + std::to_string(*light_index) +
                             (name.empty() ? "" : " '" + std::string(name) + "'");

    SceneLight light;
    LC_RETURN_IF_ERROR(read_light_emission(in, what, light));
    LC_RETURN_IF_ERROR(place_light(world, node_what, what, light));
    light.classic =
        extras_flag(in.classic, kClassicExtrasKey, what, warnings_, path_.string()) ||
        extras_flag(node.classic, kClassicExtrasKey, node_what, warnings_, path_.string());
    if (node.guid_extras == GltfNode::GuidExtras::kInvalid) {
        return fail(node_what + ": extras." + kGuidExtrasKey + " is not a GUID");
    }
    if (node.guid_extras != GltfNode::GuidExtras::kAbsent) {
        light.guid = node.guid;
    } else {
        // Stable for a given file: the light's index and name and where it hangs.
        std::vector<uint8_t> bytes;
        const std::string tag =
            "KHR_lights_punctual/" + std::to_string(*light_index) + "/" + std::string(name);
        bytes.assign(tag.begin(), tag.end());
        for (int i = 0; i < 8; ++i) bytes.push_back(uint8_t(path_hash >> (8 * i)));
        light.guid = Guid::from_bytes(bytes);
    }
    scene_.lights.push_back(light);
    return Ok{};
}

// The index of the punctual light a node names, checked against the file's lights.
Result<int> Loader::light_index_of(const GltfNode& node, const std::string& node_what) const {
    if (node.light != LightReference::kNumber) {
        return fail(node_what + ": KHR_lights_punctual extension has no 'light' index");
    }
    const double light_number = node.light_number;
    if (!(light_number >= 0.0) || light_number >= double(nodes_.lights.size()) ||
        light_number != std::floor(light_number)) {
        const bool integral =
            light_number == std::floor(light_number) && std::abs(light_number) < 1e15;
        return fail(node_what + " uses light " +
                    (integral ? std::to_string(int64_t(light_number)) : num(light_number)) +
                    ", which does not exist (the file has " + std::to_string(nodes_.lights.size()) +
                    " lights)");
    }
    return static_cast<int>(light_number);
}

// Type, colour, intensity, range and spot cone, each checked.
Status Loader::read_light_emission(const GltfPunctualLight& in, const std::string& what,
                                   SceneLight& light) const {
    const std::string_view type = nodes_.string(in.type);
    if (type == "point") {
        light.type = LightType::kPoint;
    } else if (type == "spot") {
        light.type = LightType::kSpot;
    } else if (type == "directional") {
        light.type = LightType::kDirectional;
    } else {
        return fail(what + " has unknown type '" + std::string(type) +
                    "' (expected point, spot or directional)");
    }
    if (in.color_count != 0) {
        if (in.color_count != 3) return fail(what + ": 'color' needs 3 numbers");
        for (double c : in.color) {
            if (!finite(c) || c < 0.0) {
                return fail(what + ": 'color' components must be finite and >= 0");
            }
        }
        light.color = glm::vec3(float(in.color[0]), float(in.color[1]), float(in.color[2]));
    }
    if (!finite(in.intensity)) return fail(what + ": intensity is not finite");
    if (in.intensity < 0.0) {
        return fail(what + ": negative intensity " + num(in.intensity));
    }
    if (in.intensity > double(std::numeric_limits<float>::max())) {
        return fail(what + ": intensity " + num(in.intensity) + " overflows a float");
    }
    light.intensity = float(in.intensity);
    if (!finite(in.range) || in.range < 0.0) {
        return fail(what + ": range must be finite and > 0 (absent means unbounded)");
    }
    light.range = float(in.range);
    if (light.type == LightType::kSpot) return read_spot_cone(in, what, light);
    return Ok{};
}

Status Loader::read_spot_cone(const GltfPunctualLight& in, const std::string& what, SceneLight& light) const {
    const double inner = in.inner_cone_angle;
    const double outer = in.outer_cone_angle;
    if (!finite(inner) || !finite(outer) || inner < 0.0 || outer > std::numbers::pi / 2.0 ||
        !(inner < outer)) {
        return fail(what + ": invalid spot angles (inner " + num(inner) + ", outer " + num(outer) +
                    "); need 0 <= inner < outer <= pi/2");
    }
    light.inner_cone_angle = float(inner);
    light.outer_cone_angle = float(outer);
    // Float rounding must not break inner < outer.
    if (!(light.inner_cone_angle < light.outer_cone_angle)) {
        return fail(what + ": spot angles too close to tell apart in float precision");
    }
    return Ok{};
}

// The node's transform gives the light its position and its direction (-z).
Status Loader::place_light(const glm::dmat4& world, const std::string& node_what, const std::string& what,
                           SceneLight& light) const {
    const glm::dvec4 position = world * glm::dvec4(0.0, 0.0, 0.0, 1.0);
    light.position = glm::vec3(position);
    if (!std::isfinite(light.position.x) || !std::isfinite(light.position.y) ||
        !std::isfinite(light.position.z)) {
        return fail(node_what + ": the position of " + what + " is not finite");
    }
    const glm::dvec3 direction = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
    const double length = glm::length(direction);
    if (length > 1e-12 && std::isfinite(length)) {
        light.direction = glm::vec3(direction / length);
    } else if (light.type != LightType::kPoint) {
        return fail(node_what + ": the transform of " + what + " collapses its direction (zero scale)");
    }
    return Ok{};
}

void Loader::add_camera(int node_index, int camera_index, const glm::dmat4& world) {
    const tg::Camera& in = model_.cameras[size_t(camera_index)];
    const std::string what = "camera " + std::to_string(camera_index);
    if (in.type != "perspective") {
        warn(what + " is " + in.type + "; only perspective cameras are loaded");
        return;
    }
    const double yfov = in.perspective.yfov;
    if (!finite(yfov) || yfov <= 0.0 || yfov >= std::numbers::pi) {
        warn(what + ": yfov " + num(yfov) + " is outside (0, pi); camera skipped");
        return;
    }
    const glm::dvec3 eye(world * glm::dvec4(0.0, 0.0, 0.0, 1.0));
    const glm::dvec3 forward = glm::dmat3(world) * glm::dvec3(0.0, 0.0, -1.0);
    const glm::dvec3 up = glm::dmat3(world) * glm::dvec3(0.0, 1.0, 0.0);
    const double flen = glm::length(forward);
    const double ulen = glm::length(up);
    if (!(flen > 1e-12) || !(ulen > 1e-12) || !std::isfinite(flen + ulen) ||
        !std::isfinite(eye.x + eye.y + eye.z)) {
        warn(what + " on node " + std::to_string(node_index) +
             " has a degenerate transform; camera skipped");
        return;
    }
    Camera camera;
    camera.name = !in.name.empty() ? in.name
                                   : std::string(nodes_.string(nodes_.nodes[size_t(node_index)].name));
    camera.eye = glm::vec3(eye);
    camera.up = glm::vec3(up / ulen);
    camera.yfov = float(yfov);
    scene_.cameras.push_back(camera);
    camera_forward_.push_back(forward / flen);
}

// A camera's target only fixes its direction; we put it at the distance of
// the scene's centre so that orbiting around it feels natural.
void Loader::finish_cameras() {
    const glm::dvec3 center = (glm::dvec3(scene_.bounds_min) + glm::dvec3(scene_.bounds_max)) * 0.5;
    for (size_t i = 0; i < scene_.cameras.size(); ++i) {
        Camera& camera = scene_.cameras[i];
        double distance = glm::length(center - glm::dvec3(camera.eye));
        if (!std::isfinite(distance) || distance < 1e-3) distance = 1.0;
        camera.target = glm::vec3(glm::dvec3(camera.eye) + camera_forward_[i] * distance);
    }
}

Status Loader::traverse(const std::vector<int>& roots) {
    std::vector<bool> visited(nodes_.nodes.size(), false);
    // Grown to its size at once: no second copy of a million lights while it grows.
    const auto light_nodes = std::count_if(nodes_.nodes.begin(), nodes_.nodes.end(), [](const GltfNode& node) {
        return node.light != LightReference::kNone;
    });
    scene_.lights.reserve(size_t(light_nodes));
    std::vector<glm::dmat4> parent_worlds{glm::dmat4(1.0)};  // [0]: the roots' parent
    std::vector<Traversal> stack;
    // Root by root, each subtree depth first: the order of a stack holding every root.
    for (const int root : roots) {
        stack.push_back({root, 0, 0xcbf29ce484222325ull});
        while (!stack.empty()) {
            const Traversal item = stack.back();
            stack.pop_back();
            if (visited[size_t(item.node)]) {
                return fail("node " + std::to_string(item.node) +
                            " is reached twice from the scene (listed as a root and as a descendant, "
                            "or listed twice)");
            }
            visited[size_t(item.node)] = true;
            const GltfNode& node = nodes_.nodes[size_t(item.node)];

            Result<glm::dmat4> local = local_transform(item.node);
            if (!local) return Error{local.error()};
            const glm::dmat4 world = parent_worlds[item.parent_world] * *local;
            if (!all_finite(world)) {
                return fail("node " + std::to_string(item.node) +
                            ": its world transform is not finite");
            }
            // FNV-1a step over the node index: the path from the root.
            uint64_t path_hash = item.path_hash;
            for (int i = 0; i < 4; ++i) {
                path_hash ^= uint8_t(uint32_t(item.node) >> (8 * i));
                path_hash *= 0x100000001b3ull;
            }

            if (node.mesh >= 0) {
                Status status = add_mesh(item.node, node.mesh, world);
                if (!status) return status;
            }
            if (node.camera >= 0) {
                if (node.camera >= static_cast<int>(model_.cameras.size())) {
                    return fail("node " + std::to_string(item.node) + " uses camera " +
                                std::to_string(node.camera) + ", which does not exist");
                }
                add_camera(item.node, node.camera, world);
            }
            if (node.light != LightReference::kNone) {
                Status status = add_light(item.node, world, path_hash);
                if (!status) return status;
            }
            const std::span<const int32_t> children = nodes_.children_of(node);
            if (children.empty()) continue;
            const auto world_index = uint32_t(parent_worlds.size());
            parent_worlds.push_back(world);
            for (auto it = children.rbegin(); it != children.rend(); ++it) {
                stack.push_back({*it, world_index, path_hash});
            }
        }
    }
    return Ok{};
}

// Sorted (GUID, index) pairs rather than a map: a million lights. The pair
// named is the one a scan in light order meets first: the smallest second
// index of any shared GUID, with that GUID's first index.
Status Loader::check_unique_light_guids() const {
    std::vector<std::pair<Guid, uint32_t>> order(scene_.lights.size());
    for (size_t i = 0; i < order.size(); ++i) order[i] = {scene_.lights[i].guid, uint32_t(i)};
    std::sort(order.begin(), order.end());
    size_t first = 0;
    size_t second = std::numeric_limits<size_t>::max();
    for (size_t k = 1; k < order.size(); ++k) {
        if (order[k].first == order[k - 1].first && order[k].second < second &&
            (k < 2 || order[k - 2].first != order[k].first)) {
            first = order[k - 1].second;
            second = order[k].second;
        }
    }
    if (second == std::numeric_limits<size_t>::max()) return Ok{};
    return fail("lights " + std::to_string(first) + " and " + std::to_string(second) +
                " share GUID " + scene_.lights[second].guid.to_hex());
}

Result<Scene> Loader::load_file() {
    std::filesystem::path folder = path_.parent_path();
    if (folder.empty()) folder = ".";
    {
        // The file is mapped, its pages released behind the node reader, and
        // unmapped before the scene is built: a million-light file is hundreds
        // of megabytes that nothing reads after parsing.
        Result<MappedFile> file = map_file();
        if (!file) return file.failure();
        LC_RETURN_IF_ERROR(parse(file->bytes(), folder,
                                 [&](size_t offset) { file->release_before(offset); }));
    }
    return build_scene();
}

Result<Scene> Loader::load(std::span<const uint8_t> bytes,
                           const std::filesystem::path& resource_folder) {
    LC_RETURN_IF_ERROR(parse(bytes, resource_folder));
    return build_scene();
}

Status Loader::read_environment() {
    GltfResourceAccess access(resource_folder_, options_.allow_external_resources);
    Result<GltfEnvironment> named = read_gltf_environment(model_.asset.extras, access);
    if (!named) return fail(named.error());
    scene_.environment = std::move(named->environment);
    scene_.environment_image = std::move(named->image);
    return Ok{};
}

Result<Scene> Loader::build_scene() {
    Status status = validate_node_graph();
    if (!status) return Error{status.error()};
    Result<std::vector<int>> roots = scene_roots();
    if (!roots) return Error{roots.error()};
    status = convert_materials();
    if (!status) return Error{status.error()};
    status = traverse(*roots);
    if (!status) return Error{status.error()};
    // The scene has all it needs from the table: a million light nodes'
    // records go before the GUID checks and the scene GUID allocate theirs.
    nodes_ = GltfNodeTable{};
    status = check_unique_light_guids();
    if (!status) return Error{status.error()};
    status = read_environment();
    if (!status) return Error{status.error()};
    scene_.source = path_;
    update_scene_bounds(scene_);
    finish_cameras();
    scene_.guid = compute_scene_guid(scene_);
    return std::move(scene_);
}

}  // namespace

void update_scene_bounds(Scene& scene) {
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(std::numeric_limits<float>::lowest());
    bool any = false;
    for (const Mesh& mesh : scene.meshes) {
        for (const glm::vec3& p : mesh.positions) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
            any = true;
        }
    }
    for (const SceneLight& light : scene.lights) {
        if (light.type == LightType::kDirectional) continue;
        lo = glm::min(lo, light.position);
        hi = glm::max(hi, light.position);
        any = true;
    }
    scene.bounds_min = any ? lo : glm::vec3(0.0f);
    scene.bounds_max = any ? hi : glm::vec3(0.0f);
}

Result<Scene> load_scene(const std::filesystem::path& path, std::vector<std::string>& warnings,
                         const GltfLoadOptions& options) {
    Loader loader(path, warnings, options);
    return loader.load_file();
}

Result<Scene> load_scene_from_memory(std::span<const uint8_t> bytes,
                                     const std::filesystem::path& resource_folder,
                                     std::vector<std::string>& warnings,
                                     const GltfLoadOptions& options) {
    Loader loader("(memory)", warnings, options);
    return loader.load(bytes, resource_folder);
}

Result<Scene> load_scene(const std::filesystem::path& path, const GltfLoadOptions& options) {
    std::vector<std::string> warnings;
    Result<Scene> scene = load_scene(path, warnings, options);
    for (const std::string& w : warnings) spdlog::warn("{}", w);
    return scene;
}

}  // namespace lc::client

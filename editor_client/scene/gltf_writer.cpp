// Scene -> glTF. We write the JSON ourselves (nlohmann) rather than through
// tinygltf: rewriting only the lights of an existing file must keep every
// other field, extension and external file exactly as it was, which a
// parse-and-reserialise round trip through tinygltf's model does not.
#include "editor_client/scene/gltf_writer.h"

#include <unistd.h>
#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "editor_client/scene/gltf_environment.h"
#include "editor_client/scene/gltf_loader.h"
#include "lightcuts/status_macros.h"
#include "protocol/channel_records.h"

namespace lc::client {
namespace {

using json = nlohmann::json;

constexpr const char* kLightsExtension = "KHR_lights_punctual";
constexpr const char* kEmissiveStrengthExtension = "KHR_materials_emissive_strength";
constexpr uint32_t kGlbMagic = 0x46546C67u;      // "glTF"
constexpr uint32_t kGlbChunkJson = 0x4E4F534Au;  // "JSON"
constexpr uint32_t kGlbChunkBin = 0x004E4942u;   // "BIN\0"
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;

std::string base64_encode(std::span<const uint8_t> bytes) {
    static constexpr char kAlphabet[] =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const uint32_t v =
            (uint32_t(bytes[i]) << 16) | (uint32_t(bytes[i + 1]) << 8) | bytes[i + 2];
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += kAlphabet[v & 63];
    }
    if (i + 1 == bytes.size()) {
        const uint32_t v = uint32_t(bytes[i]) << 16;
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += "==";
    } else if (i + 2 == bytes.size()) {
        const uint32_t v = (uint32_t(bytes[i]) << 16) | (uint32_t(bytes[i + 1]) << 8);
        out += kAlphabet[(v >> 18) & 63];
        out += kAlphabet[(v >> 12) & 63];
        out += kAlphabet[(v >> 6) & 63];
        out += '=';
    }
    return out;
}

bool is_glb_path(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    return ext == ".glb";
}

json vec_json(const glm::vec3& v) {
    return json::array({v.x, v.y, v.z});
}

void append_u32(std::vector<uint8_t>& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}

uint32_t read_u32(const uint8_t* p) {
    return uint32_t(p[0]) | (uint32_t(p[1]) << 8) | (uint32_t(p[2]) << 16) | (uint32_t(p[3]) << 24);
}

// The unit quaternion turning -Z (a glTF node's light direction) onto `d`.
glm::dquat rotation_from_minus_z(const glm::dvec3& d) {
    const glm::dvec3 from(0.0, 0.0, -1.0);
    const double c = glm::dot(from, d);
    if (c < -1.0 + 1e-12) return glm::dquat(0.0, 1.0, 0.0, 0.0);  // half turn about X
    const glm::dvec3 axis = glm::cross(from, d);
    return glm::normalize(glm::dquat(1.0 + c, axis.x, axis.y, axis.z));
}

// glTF writes quaternions as x, y, z, w.
json quat_json(const glm::dquat& q) {
    return json::array({q.x, q.y, q.z, q.w});
}

bool is_identity(const glm::dquat& q) {
    return std::abs(q.w - 1.0) < 1e-15 && q.x == 0.0 && q.y == 0.0 && q.z == 0.0;
}

json light_json(const SceneLight& light, size_t index) {
    json j;
    j["name"] = "light_" + std::to_string(index);
    j["type"] = light_type_name(light.type);
    j["color"] = vec_json(light.color);
    j["intensity"] = light.intensity;
    if (light.range > 0.0f) j["range"] = light.range;
    if (light.type == LightType::kSpot) {
        j["spot"] = {{"innerConeAngle", light.inner_cone_angle},
                     {"outerConeAngle", light.outer_cone_angle}};
    }
    if (light.classic) j["extras"] = {{kClassicExtrasKey, true}};
    return j;
}

json light_node_json(const SceneLight& light, size_t light_index) {
    json node;
    node["name"] = "light_" + std::to_string(light_index);
    node["translation"] = vec_json(light.position);
    const glm::dquat q = rotation_from_minus_z(glm::normalize(glm::dvec3(light.direction)));
    if (!is_identity(q)) node["rotation"] = quat_json(q);
    node["extensions"] = {{kLightsExtension, {{"light", light_index}}}};
    node["extras"] = {{kGuidExtrasKey, light.guid.to_hex()}};
    return node;
}

Status validate_lights(std::span<const SceneLight> lights) {
    for (size_t i = 0; i < lights.size(); ++i) {
        Status valid = validate_scene_light(lights[i], i);
        if (!valid) return Error{"cannot write light: " + valid.error()};
        // KHR_lights_punctual has no cosine emitter; oriented lights are
        // area-light samples the server makes, never scene lights.
        if (lights[i].type == LightType::kOriented) {
            return make_error("cannot write light " + std::to_string(i) +
                              ": glTF (KHR_lights_punctual) has no oriented light type");
        }
        if (glm::length(lights[i].direction) <= 0.0f) {
            return make_error("cannot write light " + std::to_string(i) + ": zero direction");
        }
    }
    return Ok{};
}

void add_extension_used(json& doc, const char* name) {
    if (!doc.contains("extensionsUsed") || !doc["extensionsUsed"].is_array()) {
        doc["extensionsUsed"] = json::array();
    }
    json& used = doc["extensionsUsed"];
    if (std::find(used.begin(), used.end(), name) == used.end()) used.push_back(name);
}

void remove_extension_name(json& doc, const char* list, const char* name) {
    if (!doc.contains(list) || !doc[list].is_array()) return;
    json& names = doc[list];
    names.erase(std::remove(names.begin(), names.end(), json(name)), names.end());
    if (names.empty()) doc.erase(list);
}

std::vector<uint8_t> encode_glb(std::string text, std::span<const uint8_t> bin) {
    while (text.size() % 4 != 0) text += ' ';
    const size_t bin_padded = (bin.size() + 3) / 4 * 4;
    const size_t total = 12 + 8 + text.size() + (bin.empty() ? 0 : 8 + bin_padded);
    std::vector<uint8_t> out;
    out.reserve(total);
    append_u32(out, kGlbMagic);
    append_u32(out, 2);
    append_u32(out, uint32_t(total));
    append_u32(out, uint32_t(text.size()));
    append_u32(out, kGlbChunkJson);
    out.insert(out.end(), text.begin(), text.end());
    if (!bin.empty()) {
        append_u32(out, uint32_t(bin_padded));
        append_u32(out, kGlbChunkBin);
        out.insert(out.end(), bin.begin(), bin.end());
        out.resize(out.size() + (bin_padded - bin.size()), 0);
    }
    return out;
}

Status write_file_atomically(const std::filesystem::path& out,
                             const std::function<void(std::ostream&)>& write) {
    std::error_code ec;
    const std::filesystem::path dir = out.has_parent_path() ? out.parent_path() : ".";
    if (!std::filesystem::is_directory(dir, ec)) {
        return make_error("cannot write " + out.string() + ": folder " + dir.string() +
                          " does not exist");
    }
    std::filesystem::path tmp = out;
    tmp += ".tmp-" + std::to_string(::getpid());
    {
        std::ofstream file(tmp, std::ios::binary | std::ios::trunc);
        if (!file) return make_error("cannot write " + out.string() + ": cannot create the file");
        write(file);
        file.flush();
        if (!file) {
            file.close();
            std::filesystem::remove(tmp, ec);
            return make_error("cannot write " + out.string() + ": write failed (disk full?)");
        }
    }
    std::filesystem::rename(tmp, out, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        return make_error("cannot write " + out.string() + ": " + ec.message());
    }
    return Ok{};
}

Status write_file_atomically(const std::filesystem::path& out, std::span<const uint8_t> bytes) {
    return write_file_atomically(out, [&](std::ostream& file) {
        file.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    });
}

// The elements of one array written in place of a marker string in the
// document, one element's JSON at a time: a million lights are never a
// million nlohmann objects at once (4 GB at 2^20 lights).
struct StreamedArray {
    json::json_pointer array;
    std::string marker;  // the array's last element in `doc` until it is written
    size_t count = 0;
    std::function<json(size_t)> element;
};

// Each marker stands once in the text: no string of the scene's spells one.
bool markers_stand_alone(const std::string& text, const std::vector<StreamedArray>& arrays) {
    for (const StreamedArray& array : arrays) {
        const std::string quoted = json(array.marker).dump();
        const size_t first = text.find(quoted);
        if (first == std::string::npos || text.find(quoted, first + 1) != std::string::npos) return false;
    }
    return true;
}

// `doc`'s text as dump(indent) gives it, each marker's array elements in its
// place, handed to `out` a piece at a time. An element dumped alone is
// indented from column 0: every line it breaks is moved right to where the
// marker stood, which is the text dump(indent) gives for the whole array.
void write_json(json& doc, int indent, const std::vector<StreamedArray>& arrays,
                const std::function<void(std::string_view)>& out) {
    std::string text = doc.dump(indent);
    if (!markers_stand_alone(text, arrays)) {
        // A scene string that spells a marker: the arrays are made whole in the document.
        for (const StreamedArray& array : arrays) {
            json& elements = doc[array.array];
            elements.erase(elements.size() - 1);
            for (size_t i = 0; i < array.count; ++i) elements.push_back(array.element(i));
        }
        out(doc.dump(indent));
        return;
    }
    std::vector<std::pair<size_t, const StreamedArray*>> places;
    for (const StreamedArray& array : arrays) {
        const std::string quoted = json(array.marker).dump();
        places.emplace_back(text.find(quoted), &array);
    }
    std::sort(places.begin(), places.end());
    size_t at = 0;
    for (const auto& [place, array] : places) {
        out(std::string_view(text).substr(at, place - at));
        const size_t line_start = text.rfind('\n', place) + 1;
        const std::string break_and_indent = "\n" + text.substr(line_start, place - line_start);
        for (size_t i = 0; i < array->count; ++i) {
            if (i > 0) out(indent < 0 ? "," : "," + break_and_indent);
            std::string element = array->element(i).dump(indent);
            if (indent >= 0) {
                for (size_t nl = element.find('\n'); nl != std::string::npos; nl = element.find('\n', nl + 1)) {
                    element.replace(nl, 1, break_and_indent);
                    nl += break_and_indent.size() - 1;
                }
            }
            out(element);
        }
        at = place + json(array->marker).dump().size();
    }
    out(std::string_view(text).substr(at));
}

// Writes `doc` to `out` as .glb (with `bin` as its binary chunk) or as .gltf
// (with `bin` embedded as base64 in buffer `bin_buffer`), with `arrays`
// written in place of their markers.
Status write_document(json doc, std::span<const uint8_t> bin, int bin_buffer,
                      const std::filesystem::path& out, const std::vector<StreamedArray>& arrays = {}) {
    if (is_glb_path(out)) {
        std::string text;
        write_json(doc, -1, arrays, [&](std::string_view piece) { text += piece; });
        const std::vector<uint8_t> bytes = encode_glb(std::move(text), bin);
        return write_file_atomically(out, bytes);
    }
    if (bin_buffer >= 0) {
        doc["buffers"][size_t(bin_buffer)]["uri"] =
            "data:application/octet-stream;base64," + base64_encode(bin);
    }
    return write_file_atomically(out, [&](std::ostream& file) {
        write_json(doc, 2, arrays, [&](std::string_view piece) {
            file.write(piece.data(), std::streamsize(piece.size()));
        });
        file << "\n";
    });
}

// --- Whole-scene writer -------------------------------------------------------

class BinaryBuilder {
public:
    // Appends floats or uint32s as one bufferView and returns its index.
    template <typename T>
    int add_view(json& doc, const std::vector<T>& items, int target) {
        while (bytes_.size() % 4 != 0) bytes_.push_back(0);
        const size_t offset = bytes_.size();
        const size_t size = items.size() * sizeof(T);
        bytes_.resize(offset + size);
        if (size > 0) std::memcpy(bytes_.data() + offset, items.data(), size);
        json view = {
            {"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}, {"target", target}};
        doc["bufferViews"].push_back(view);
        return int(doc["bufferViews"].size() - 1);
    }
    const std::vector<uint8_t>& bytes() const { return bytes_; }

private:
    std::vector<uint8_t> bytes_;
};

int add_accessor(json& doc, int view, int component_type, size_t count, const char* type) {
    doc["accessors"].push_back({{"bufferView", view},
                                {"componentType", component_type},
                                {"count", count},
                                {"type", type}});
    return int(doc["accessors"].size() - 1);
}

json material_json(const Material& m, bool& uses_emissive_strength) {
    json j;
    j["pbrMetallicRoughness"] = {
        {"baseColorFactor", json::array({m.base_color_factor.r, m.base_color_factor.g,
                                         m.base_color_factor.b, m.base_color_factor.a})},
        {"metallicFactor", m.metallic},
        {"roughnessFactor", m.roughness}};
    // Core glTF caps emissiveFactor at 1; brighter emission goes to emissive_strength.
    const float peak = std::max({m.emissive_factor.r, m.emissive_factor.g, m.emissive_factor.b});
    if (peak > 1.0f) {
        j["emissiveFactor"] = vec_json(m.emissive_factor / peak);
        j["extensions"] = {{kEmissiveStrengthExtension, {{"emissiveStrength", peak}}}};
        uses_emissive_strength = true;
    } else if (peak > 0.0f) {
        j["emissiveFactor"] = vec_json(m.emissive_factor);
    }
    return j;
}

bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// The camera's node rotation: local +X right, +Y up, -Z towards the target.
Result<glm::dquat> camera_rotation(const Camera& camera) {
    const glm::dvec3 forward = glm::dvec3(camera.target) - glm::dvec3(camera.eye);
    if (!(glm::length(forward) > 0.0)) return make_error("its eye and target coincide");
    const glm::dvec3 f = glm::normalize(forward);
    glm::dvec3 up = glm::dvec3(camera.up);
    glm::dvec3 right = glm::cross(f, up);
    if (!(glm::length(right) > 1e-9)) {
        // Looking along `up`: any perpendicular up will do.
        up = std::abs(f.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
        right = glm::cross(f, up);
    }
    right = glm::normalize(right);
    const glm::dvec3 true_up = glm::cross(right, f);
    const glm::dmat3 basis(right, true_up, -f);
    return glm::normalize(glm::quat_cast(basis));
}

// Why `scene`'s mesh `m` cannot be written, if it cannot.
Status check_writable_mesh(const Scene& scene, size_t m) {
    const Mesh& mesh = scene.meshes[m];
    const std::string what = "mesh " + std::to_string(m);
    if (mesh.normals.size() != mesh.positions.size()) {
        return make_error("cannot write " + what + ": " + std::to_string(mesh.normals.size()) +
                          " normals for " + std::to_string(mesh.positions.size()) + " positions");
    }
    if (!mesh.uvs.empty() && mesh.uvs.size() != mesh.positions.size()) {
        return make_error("cannot write " + what + ": uv count differs from position count");
    }
    if (mesh.material >= static_cast<int>(scene.materials.size()) || mesh.material < -1) {
        return make_error("cannot write " + what + ": material " + std::to_string(mesh.material) +
                          " does not exist");
    }
    for (const glm::vec3& p : mesh.positions) {
        if (!finite3(p)) return make_error("cannot write " + what + ": non-finite position");
    }
    for (const glm::vec3& n : mesh.normals) {
        if (!finite3(n)) return make_error("cannot write " + what + ": non-finite normal");
    }
    for (uint32_t index : mesh.indices) {
        if (index >= mesh.positions.size()) {
            return make_error("cannot write " + what + ": index " + std::to_string(index) +
                              " out of range of " + std::to_string(mesh.positions.size()) + " vertices");
        }
    }
    return Ok{};
}

// A checked mesh as a mesh, its accessors and a node of the scene.
void add_mesh(json& doc, BinaryBuilder& bin, const Mesh& mesh, size_t m) {
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(std::numeric_limits<float>::lowest());
    for (const glm::vec3& p : mesh.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    json attributes;
    const int pos = add_accessor(doc, bin.add_view(doc, mesh.positions, kArrayBuffer), kFloat,
                                 mesh.positions.size(), "VEC3");
    doc["accessors"][size_t(pos)]["min"] = vec_json(lo);
    doc["accessors"][size_t(pos)]["max"] = vec_json(hi);
    attributes["POSITION"] = pos;
    attributes["NORMAL"] = add_accessor(doc, bin.add_view(doc, mesh.normals, kArrayBuffer), kFloat,
                                        mesh.normals.size(), "VEC3");
    if (!mesh.uvs.empty()) {
        attributes["TEXCOORD_0"] = add_accessor(doc, bin.add_view(doc, mesh.uvs, kArrayBuffer), kFloat,
                                                mesh.uvs.size(), "VEC2");
    }
    const int indices = add_accessor(doc, bin.add_view(doc, mesh.indices, kElementArrayBuffer),
                                     kUnsignedInt, mesh.indices.size(), "SCALAR");
    json primitive = {{"attributes", attributes}, {"indices", indices}, {"mode", 4}};
    if (mesh.material >= 0) primitive["material"] = mesh.material;
    doc["meshes"].push_back({{"primitives", json::array({primitive})}});
    doc["nodes"].push_back({{"name", "mesh_" + std::to_string(m)}, {"mesh", doc["meshes"].size() - 1}});
    doc["scenes"][0]["nodes"].push_back(doc["nodes"].size() - 1);
}

Status add_cameras(json& doc, const Scene& scene) {
    // Near plane: a small fraction of the scene's size (the loader ignores it).
    const float diagonal = glm::length(scene.bounds_max - scene.bounds_min);
    const double znear = std::max(1e-3, 1e-4 * double(diagonal));
    for (size_t c = 0; c < scene.cameras.size(); ++c) {
        const Camera& camera = scene.cameras[c];
        if (!finite3(camera.eye) || !finite3(camera.target) || !finite3(camera.up) ||
            !(camera.yfov > 0.0f && camera.yfov < 3.14159f)) {
            return make_error("cannot write camera " + std::to_string(c) +
                              ": non-finite placement or yfov outside (0, pi)");
        }
        Result<glm::dquat> rotation = camera_rotation(camera);
        if (!rotation) {
            return make_error("cannot write camera " + std::to_string(c) + ": " + rotation.error());
        }
        if (!doc.contains("cameras")) doc["cameras"] = json::array();
        doc["cameras"].push_back({{"name", camera.name},
                                  {"type", "perspective"},
                                  {"perspective", {{"yfov", camera.yfov}, {"znear", znear}}}});
        doc["nodes"].push_back(
            {{"name", camera.name.empty() ? "camera_" + std::to_string(c) : camera.name},
             {"camera", doc["cameras"].size() - 1},
             {"translation", vec_json(camera.eye)},
             {"rotation", quat_json(*rotation)}});
        doc["scenes"][0]["nodes"].push_back(doc["nodes"].size() - 1);
    }
    return Ok{};
}

// The light nodes follow the others; both arrays are written as they are
// dumped: here only their markers, the streamed arrays returned.
std::vector<StreamedArray> add_streamed_lights(json& doc, const Scene& scene) {
    if (scene.lights.empty()) return {};
    const StreamedArray light_nodes{json::json_pointer("/nodes"), "lightcuts-writer:light-nodes",
                                    scene.lights.size(),
                                    [&list = scene.lights](size_t i) { return light_node_json(list[i], i); }};
    const StreamedArray lights{json::json_pointer(std::string("/extensions/") + kLightsExtension + "/lights"),
                               "lightcuts-writer:lights", scene.lights.size(),
                               [&list = scene.lights](size_t i) { return light_json(list[i], i); }};
    json& scene_nodes = doc["scenes"][0]["nodes"];
    for (size_t i = 0; i < scene.lights.size(); ++i) scene_nodes.push_back(doc["nodes"].size() + i);
    doc["nodes"].push_back(light_nodes.marker);
    doc["extensions"][kLightsExtension] = {{"lights", json::array({lights.marker})}};
    add_extension_used(doc, kLightsExtension);
    return {light_nodes, lights};
}

}  // namespace

Status write_scene_gltf(const Scene& scene, const std::filesystem::path& out) {
    Status valid = validate_lights(scene.lights);
    if (!valid) return valid;
    json doc;
    doc["asset"] = {{"version", "2.0"}, {"generator", "lightcuts editor_client"}};
    put_gltf_environment(scene, std::filesystem::absolute(out).parent_path(), doc["asset"]);
    doc["scene"] = 0;
    doc["scenes"] = json::array({json::object({{"nodes", json::array()}})});
    doc["nodes"] = json::array();
    doc["meshes"] = json::array();
    doc["accessors"] = json::array();
    doc["bufferViews"] = json::array();

    bool uses_emissive_strength = false;
    if (!scene.materials.empty()) {
        doc["materials"] = json::array();
        for (const Material& m : scene.materials) {
            doc["materials"].push_back(material_json(m, uses_emissive_strength));
        }
    }
    BinaryBuilder bin;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        if (mesh.indices.empty() || mesh.positions.empty()) continue;
        LC_RETURN_IF_ERROR(check_writable_mesh(scene, m));
        add_mesh(doc, bin, mesh, m);
    }
    LC_RETURN_IF_ERROR(add_cameras(doc, scene));
    const std::vector<StreamedArray> streamed = add_streamed_lights(doc, scene);
    if (uses_emissive_strength) add_extension_used(doc, kEmissiveStrengthExtension);

    // Empty arrays are invalid glTF.
    for (const char* key : {"meshes", "accessors", "bufferViews", "nodes"}) {
        if (doc[key].empty()) doc.erase(key);
    }
    int bin_buffer = -1;
    if (!bin.bytes().empty()) {
        doc["buffers"] = json::array({json::object({{"byteLength", bin.bytes().size()}})});
        bin_buffer = 0;
    }
    return write_document(std::move(doc), bin.bytes(), bin_buffer, out, streamed);
}

// --- Light replacement in an existing file ---------------------------------------

namespace {

struct SourceDocument {
    json doc;
    std::vector<uint8_t> bin;  // a .glb's binary chunk
    bool binary = false;
};

Result<SourceDocument> read_source(const std::filesystem::path& source) {
    std::ifstream file(source, std::ios::binary);
    if (!file) return make_error(source.string() + ": cannot open the file");
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(file)),
                               std::istreambuf_iterator<char>());
    SourceDocument out;
    std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (bytes.size() >= 4 && read_u32(bytes.data()) == kGlbMagic) {
        out.binary = true;
        if (bytes.size() < 20)
            return make_error(source.string() + ": truncated glTF binary header");
        const uint32_t version = read_u32(bytes.data() + 4);
        const uint32_t length = read_u32(bytes.data() + 8);
        if (version != 2) {
            return make_error(source.string() + ": glTF binary version " + std::to_string(version) +
                              " (expected 2)");
        }
        if (length > bytes.size()) {
            return make_error(source.string() + ": glTF binary claims " + std::to_string(length) +
                              " bytes but the file has " + std::to_string(bytes.size()));
        }
        size_t at = 12;
        bool have_json = false;
        while (at + 8 <= length) {
            const uint32_t chunk_length = read_u32(bytes.data() + at);
            const uint32_t chunk_type = read_u32(bytes.data() + at + 4);
            if (chunk_length > length - at - 8) {
                return make_error(source.string() + ": glTF binary chunk runs past the end");
            }
            const uint8_t* data = bytes.data() + at + 8;
            if (!have_json) {
                if (chunk_type != kGlbChunkJson) {
                    return make_error(source.string() +
                                      ": the first glTF binary chunk is not JSON");
                }
                text = std::string_view(reinterpret_cast<const char*>(data), chunk_length);
                have_json = true;
            } else if (chunk_type == kGlbChunkBin && out.bin.empty()) {
                out.bin.assign(data, data + chunk_length);
            }
            at += 8 + size_t(chunk_length);
        }
        if (!have_json) return make_error(source.string() + ": glTF binary without a JSON chunk");
    }
    out.doc = json::parse(text.begin(), text.end(), nullptr, false);
    if (out.doc.is_discarded()) return make_error(source.string() + ": bad JSON");
    if (!out.doc.is_object())
        return make_error(source.string() + ": the JSON root is not an object");
    return out;
}

bool is_relative_uri(const std::string& uri) {
    if (uri.empty() || uri.rfind("data:", 0) == 0 || uri.front() == '/') return false;
    return uri.find("://") == std::string::npos;
}

std::string percent_decode(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
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

// External files stay where they are; only the way to reach them changes.
void rewrite_uris(json& doc, const std::filesystem::path& source,
                  const std::filesystem::path& out) {
    const std::filesystem::path from =
        std::filesystem::absolute(source).parent_path().lexically_normal();
    const std::filesystem::path to =
        std::filesystem::absolute(out).parent_path().lexically_normal();
    if (from == to) return;
    for (const char* key : {"buffers", "images"}) {
        if (!doc.contains(key) || !doc[key].is_array()) continue;
        for (json& item : doc[key]) {
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
        json& map = doc["asset"]["extras"][kEnvironmentExtrasKey];
        if (map.is_object() && map.contains("image") && map["image"].is_string()) {
            const std::filesystem::path image(map["image"].get<std::string>());
            if (image.is_relative()) map["image"] = path_from(to, from / image);
        }
    }
}

int target_scene(const json& doc) {
    if (!doc.contains("scenes") || !doc["scenes"].is_array() || doc["scenes"].empty()) return -1;
    if (doc.contains("scene") && doc["scene"].is_number_integer()) {
        const int64_t s = doc["scene"].get<int64_t>();
        if (s >= 0 && s < int64_t(doc["scenes"].size())) return int(s);
    }
    return 0;
}

// Nodes we must not reuse: children, skin joints, animation targets.
std::set<int64_t> referenced_nodes(const json& doc) {
    std::set<int64_t> referenced;
    for (const json& node : doc["nodes"]) {
        if (node.is_object() && node.contains("children") && node["children"].is_array()) {
            for (const json& c : node["children"])
                if (c.is_number_integer()) referenced.insert(c.get<int64_t>());
        }
    }
    if (doc.contains("skins") && doc["skins"].is_array()) {
        for (const json& skin : doc["skins"]) {
            if (!skin.is_object()) continue;
            if (skin.contains("skeleton") && skin["skeleton"].is_number_integer())
                referenced.insert(skin["skeleton"].get<int64_t>());
            if (skin.contains("joints") && skin["joints"].is_array())
                for (const json& j : skin["joints"])
                    if (j.is_number_integer()) referenced.insert(j.get<int64_t>());
        }
    }
    if (doc.contains("animations") && doc["animations"].is_array()) {
        for (const json& anim : doc["animations"]) {
            if (!anim.is_object() || !anim.contains("channels") || !anim["channels"].is_array()) continue;
            for (const json& ch : anim["channels"]) {
                if (ch.is_object() && ch.contains("target") && ch["target"].is_object() &&
                    ch["target"].contains("node") && ch["target"]["node"].is_number_integer())
                    referenced.insert(ch["target"]["node"].get<int64_t>());
            }
        }
    }
    return referenced;
}

std::set<int64_t> scene_roots(const json& doc, int scene_index) {
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
    const std::set<int64_t> in_scene = scene_roots(doc, scene_index);
    json& nodes = doc["nodes"];
    std::vector<size_t> reusable;
    for (size_t i = 0; i < nodes.size(); ++i) {
        json& node = nodes[i];
        if (!node.is_object() || !node.contains("extensions") || !node["extensions"].is_object() ||
            !node["extensions"].contains(kLightsExtension)) {
            continue;
        }
        node["extensions"].erase(kLightsExtension);
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
            doc["extensions"].erase(kLightsExtension);
            if (doc["extensions"].empty()) doc.erase("extensions");
        }
        remove_extension_name(doc, "extensionsUsed", kLightsExtension);
        remove_extension_name(doc, "extensionsRequired", kLightsExtension);
        return;
    }
    json light_list = json::array();
    for (size_t k = 0; k < lights.size(); ++k) light_list.push_back(light_json(lights[k], k));
    if (!doc.contains("extensions") || !doc["extensions"].is_object()) doc["extensions"] = json::object();
    doc["extensions"][kLightsExtension] = {{"lights", light_list}};
    add_extension_used(doc, kLightsExtension);
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

Status write_lights_into_gltf(const std::filesystem::path& source,
                              std::span<const SceneLight> lights,
                              const std::filesystem::path& out) {
    Status valid = validate_lights(lights);
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
        return write_document(std::move(doc), src.bin, *bin_buffer, out);
    } catch (const json::exception& e) {
        return make_error(source.string() + ": unexpected JSON structure: " + e.what());
    }
}

}  // namespace lc::client

// Scene -> a new glTF. We write the JSON ourselves (nlohmann) rather than
// through tinygltf, as the light patcher must (gltf_light_patcher.cpp), so
// both writers share the light JSON and the document output.
#include "editor_client/scene/gltf/writer/gltf_scene_writer.h"

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "editor_client/scene/gltf/writer/gltf_document_output.h"
#include "editor_client/scene/gltf/gltf_environment.h"
#include "editor_client/scene/gltf/gltf_json_values.h"
#include "editor_client/scene/gltf/writer/gltf_light_json.h"
#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

using json = nlohmann::json;

constexpr const char* kEmissiveStrengthExtension = "KHR_materials_emissive_strength";
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;
constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;

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
        json view = {{"buffer", 0}, {"byteOffset", offset}, {"byteLength", size}, {"target", target}};
        doc["bufferViews"].push_back(view);
        return int(doc["bufferViews"].size() - 1);
    }
    const std::vector<uint8_t>& bytes() const { return bytes_; }

private:
    std::vector<uint8_t> bytes_;
};

int add_accessor(json& doc, int view, int component_type, size_t count, const char* type) {
    doc["accessors"].push_back(
        {{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}});
    return int(doc["accessors"].size() - 1);
}

json material_json(const Material& m, bool& uses_emissive_strength) {
    json j;
    j["pbrMetallicRoughness"] = {
        {"baseColorFactor", json::array({m.base_color_factor.r, m.base_color_factor.g, m.base_color_factor.b,
                                         m.base_color_factor.a})},
        {"metallicFactor", m.metallic},
        {"roughnessFactor", m.roughness}};
    // Core glTF caps emissiveFactor at 1; brighter emission goes to emissive_strength.
    const float peak = std::max({m.emissive_factor.r, m.emissive_factor.g, m.emissive_factor.b});
    if (peak > 1.0f) {
        j["emissiveFactor"] = gltf_vec3_json(m.emissive_factor / peak);
        j["extensions"] = {{kEmissiveStrengthExtension, {{"emissiveStrength", peak}}}};
        uses_emissive_strength = true;
    } else if (peak > 0.0f) {
        j["emissiveFactor"] = gltf_vec3_json(m.emissive_factor);
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
void add_mesh_node(json& doc, BinaryBuilder& bin, const Mesh& mesh, size_t m) {
    glm::vec3 lo(std::numeric_limits<float>::max());
    glm::vec3 hi(std::numeric_limits<float>::lowest());
    for (const glm::vec3& p : mesh.positions) {
        lo = glm::min(lo, p);
        hi = glm::max(hi, p);
    }
    json attributes;
    const int pos = add_accessor(doc, bin.add_view(doc, mesh.positions, kArrayBuffer), kFloat,
                                 mesh.positions.size(), "VEC3");
    doc["accessors"][size_t(pos)]["min"] = gltf_vec3_json(lo);
    doc["accessors"][size_t(pos)]["max"] = gltf_vec3_json(hi);
    attributes["POSITION"] = pos;
    attributes["NORMAL"] =
        add_accessor(doc, bin.add_view(doc, mesh.normals, kArrayBuffer), kFloat, mesh.normals.size(), "VEC3");
    if (!mesh.uvs.empty()) {
        attributes["TEXCOORD_0"] =
            add_accessor(doc, bin.add_view(doc, mesh.uvs, kArrayBuffer), kFloat, mesh.uvs.size(), "VEC2");
    }
    const int indices = add_accessor(doc, bin.add_view(doc, mesh.indices, kElementArrayBuffer), kUnsignedInt,
                                     mesh.indices.size(), "SCALAR");
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
        doc["nodes"].push_back({{"name", camera.name.empty() ? "camera_" + std::to_string(c) : camera.name},
                                {"camera", doc["cameras"].size() - 1},
                                {"translation", gltf_vec3_json(camera.eye)},
                                {"rotation", gltf_quat_json(*rotation)}});
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
    const StreamedArray lights{
        json::json_pointer(std::string("/extensions/") + kLightsPunctualExtension + "/lights"),
        "lightcuts-writer:lights", scene.lights.size(),
        [&list = scene.lights](size_t i) { return light_json(list[i], i); }};
    json& scene_nodes = doc["scenes"][0]["nodes"];
    for (size_t i = 0; i < scene.lights.size(); ++i) scene_nodes.push_back(doc["nodes"].size() + i);
    doc["nodes"].push_back(light_nodes.marker);
    doc["extensions"][kLightsPunctualExtension] = {{"lights", json::array({lights.marker})}};
    add_extension_used(doc, kLightsPunctualExtension);
    return {light_nodes, lights};
}

// The materials' factors (textures are not written); true when one needs
// KHR_materials_emissive_strength.
bool add_materials(json& doc, const Scene& scene) {
    bool uses_emissive_strength = false;
    if (scene.materials.empty()) return false;
    doc["materials"] = json::array();
    for (const Material& m : scene.materials)
        doc["materials"].push_back(material_json(m, uses_emissive_strength));
    return uses_emissive_strength;
}

}  // namespace

Status write_scene_gltf(const Scene& scene, const std::filesystem::path& out) {
    Status valid = validate_lights_for_gltf(scene.lights);
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

    const bool uses_emissive_strength = add_materials(doc, scene);
    BinaryBuilder bin;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        if (mesh.indices.empty() || mesh.positions.empty()) continue;
        LC_RETURN_IF_ERROR(check_writable_mesh(scene, m));
        add_mesh_node(doc, bin, mesh, m);
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
    return write_gltf_document(std::move(doc), bin.bytes(), bin_buffer, out, streamed);
}

}  // namespace lc::client

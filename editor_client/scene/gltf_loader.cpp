// glTF 2.0 -> Scene, orchestrated. The node reader (simdjson) takes the
// nodes, scenes and punctual lights into a flat table when the file is in
// its plain form, and tinygltf parses the rest and the buffers (or
// everything, otherwise: the table is then filled from tinygltf's model).
// Then the node graph is checked, the materials read, and the scene's nodes
// walked, each node's mesh, camera and light read by its own reader
// (gltf_mesh_reader.h, gltf_camera_reader.h, gltf_light_reader.h). Everything
// neither parser checks (index ranges, accessor extents, finiteness, the node
// graph) is checked before any byte is read, so a broken file gives an error
// and never a crash.
#include "editor_client/scene/gltf_loader.h"

#include <tiny_gltf.h>  // Debian's shared library: no TINYGLTF_IMPLEMENTATION here

#include <spdlog/spdlog.h>
#include <glm/common.hpp>
#include <glm/mat4x4.hpp>

#include <algorithm>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "editor_client/scene/gltf_camera_reader.h"
#include "editor_client/scene/gltf_diagnostics.h"
#include "editor_client/scene/gltf_environment.h"
#include "editor_client/scene/gltf_finite.h"
#include "editor_client/scene/gltf_light_reader.h"
#include "editor_client/scene/gltf_material_reader.h"
#include "editor_client/scene/gltf_mesh_reader.h"
#include "editor_client/scene/gltf_model_nodes.h"
#include "editor_client/scene/gltf_node_graph.h"
#include "editor_client/scene/gltf_node_reader.h"
#include "editor_client/scene/gltf_resource_access.h"
#include "editor_client/scene/gltf_tinygltf_parse.h"
#include "editor_client/scene/mapped_file.h"
#include "editor_client/scene/scene_guid.h"
#include "lightcuts/status_macros.h"

namespace lc::client {
namespace {

namespace tg = tinygltf;

// A node waiting to be visited. Its parent's world transform is shared by
// index (parent_worlds in traverse): a node with a million children, or a
// scene with a million roots, waits as a million small entries.
struct Traversal {
    int node = 0;
    uint32_t parent_world = 0;
    uint64_t path_hash = 0;
};

// FNV-1a step over a node index: the path from the root.
uint64_t extend_path_hash(uint64_t path_hash, int node) {
    for (int i = 0; i < 4; ++i) {
        path_hash ^= uint8_t(uint32_t(node) >> (8 * i));
        path_hash *= 0x100000001b3ull;
    }
    return path_hash;
}

// What the walk hands each node's parts to.
struct NodeReaders {
    GltfMeshReader meshes;
    GltfCameraReader cameras;
    GltfLightReader lights;
};

class Loader {
public:
    // `path` names the file in messages and in Scene::source.
    Loader(const std::filesystem::path& path, std::vector<std::string>& warnings,
           const GltfLoadOptions& options)
        : path_(path), diagnostics_(path.string(), warnings), options_(options) {}

    Result<Scene> load_file();
    // `resource_folder` stands for the scene's folder (gltf_loader.h).
    Result<Scene> load(std::span<const uint8_t> bytes, const std::filesystem::path& resource_folder);

private:
    Result<MappedFile> map_file() const;
    // `on_consumed`: the node reader will not read the bytes before an offset again.
    Status parse(std::span<const uint8_t> bytes, const std::filesystem::path& resource_folder,
                 const ConsumedBytes& on_consumed = {});
    // The fast path: false when it does not take the file.
    bool parse_streamed(std::span<const uint8_t> bytes, const std::filesystem::path& resource_folder,
                        const ConsumedBytes& on_consumed);
    // The rest of the load, once the file's bytes are parsed.
    Result<Scene> build_scene();
    Status traverse(const std::vector<int>& roots, NodeReaders& readers);
    Status visit(const Traversal& item, const glm::dmat4& world, uint64_t path_hash, NodeReaders& readers);
    Status read_environment();

    std::filesystem::path path_;
    GltfDiagnostics diagnostics_;
    GltfLoadOptions options_;
    std::filesystem::path resource_folder_;  // as parse() was given it
    tg::Model model_;
    // Nodes, scenes and punctual lights: read by gltf_node_reader, or taken
    // from model_ (whose copies are then dropped).
    GltfNodeTable nodes_;
    Scene scene_;
};

Result<MappedFile> Loader::map_file() const {
    std::error_code ec;
    if (!std::filesystem::exists(path_, ec)) return diagnostics_.fail("file does not exist");
    if (!std::filesystem::is_regular_file(path_, ec)) return diagnostics_.fail("not a regular file");
    Result<MappedFile> file = MappedFile::open(path_);
    if (!file) return diagnostics_.fail(file.error());
    return file;
}

Status Loader::parse(std::span<const uint8_t> bytes, const std::filesystem::path& resource_folder,
                     const ConsumedBytes& on_consumed) {
    resource_folder_ = resource_folder;
    if (bytes.empty()) return diagnostics_.fail("the file is empty");
    if (bytes.size() > std::numeric_limits<unsigned int>::max()) {
        return diagnostics_.fail("the file is larger than 4 GiB");
    }
    if (options_.stream_nodes && parse_streamed(bytes, resource_folder, on_consumed)) return Ok{};
    LC_RETURN_IF_ERROR(
        parse_with_tinygltf(bytes, resource_folder, options_.allow_external_resources, model_, diagnostics_));
    nodes_ = node_table_from(model_);
    // New vectors, not `= {}`: that clears and keeps a million nodes' capacity.
    model_.nodes = std::vector<tg::Node>();
    model_.lights = std::vector<tg::Light>();
    model_.scenes = std::vector<tg::Scene>();
    return Ok{};
}

bool Loader::parse_streamed(std::span<const uint8_t> bytes, const std::filesystem::path& resource_folder,
                            const ConsumedBytes& on_consumed) {
    std::optional<GltfNodeSplit> split = read_gltf_nodes(bytes, on_consumed);
    if (!split) return false;
    // Its warnings count only if tinygltf takes the remainder.
    std::vector<std::string> warnings;
    GltfDiagnostics remainder_diagnostics(diagnostics_.file(), warnings);
    const auto* remainder = reinterpret_cast<const uint8_t*>(split->remainder.data());
    if (!parse_with_tinygltf({remainder, split->remainder.size()}, resource_folder,
                             options_.allow_external_resources, model_, remainder_diagnostics)) {
        // The whole file through tinygltf gives the message it always gave.
        model_ = tg::Model{};
        return false;
    }
    nodes_ = std::move(split->table);
    diagnostics_.take_warnings(warnings);
    return true;
}

Status Loader::traverse(const std::vector<int>& roots, NodeReaders& readers) {
    std::vector<bool> visited(nodes_.nodes.size(), false);
    // Grown to its size at once: no second copy of a million lights while it grows.
    const auto light_nodes =
        std::count_if(nodes_.nodes.begin(), nodes_.nodes.end(),
                      [](const GltfNode& node) { return node.light != LightReference::kNone; });
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
                return diagnostics_.fail("node " + std::to_string(item.node) +
                                         " is reached twice from the scene (listed as a root and as a "
                                         "descendant, or listed twice)");
            }
            visited[size_t(item.node)] = true;
            Result<glm::dmat4> local = gltf_local_transform(nodes_, item.node, diagnostics_);
            if (!local) return local.failure();
            const glm::dmat4 world = parent_worlds[item.parent_world] * *local;
            const uint64_t path_hash = extend_path_hash(item.path_hash, item.node);
            LC_RETURN_IF_ERROR(visit(item, world, path_hash, readers));
            const std::span<const int32_t> children = nodes_.children_of(nodes_.nodes[size_t(item.node)]);
            if (children.empty()) continue;
            const auto world_index = uint32_t(parent_worlds.size());
            parent_worlds.push_back(world);
            for (auto it = children.rbegin(); it != children.rend(); ++it)
                stack.push_back({*it, world_index, path_hash});
        }
    }
    return Ok{};
}

// The node's mesh, camera and light, in that order.
Status Loader::visit(const Traversal& item, const glm::dmat4& world, uint64_t path_hash,
                     NodeReaders& readers) {
    if (!all_finite(world)) {
        return diagnostics_.fail("node " + std::to_string(item.node) + ": its world transform is not finite");
    }
    const GltfNode& node = nodes_.nodes[size_t(item.node)];
    if (node.mesh >= 0) LC_RETURN_IF_ERROR(readers.meshes.add_mesh(item.node, node.mesh, world));
    if (node.camera >= 0) LC_RETURN_IF_ERROR(readers.cameras.add(item.node, node.camera, world, scene_));
    if (node.light != LightReference::kNone) {
        Result<SceneLight> light = readers.lights.read(item.node, world, path_hash);
        if (!light) return light.failure();
        scene_.lights.push_back(*light);
    }
    return Ok{};
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
        LC_RETURN_IF_ERROR(
            parse(file->bytes(), folder, [&](size_t offset) { file->release_before(offset); }));
    }
    return build_scene();
}

Result<Scene> Loader::load(std::span<const uint8_t> bytes, const std::filesystem::path& resource_folder) {
    LC_RETURN_IF_ERROR(parse(bytes, resource_folder));
    return build_scene();
}

Status Loader::read_environment() {
    GltfResourceAccess access(resource_folder_, options_.allow_external_resources);
    Result<GltfEnvironment> named = read_gltf_environment(model_.asset.extras, access);
    if (!named) return diagnostics_.fail(named.error());
    scene_.environment = std::move(named->environment);
    scene_.environment_image = std::move(named->image);
    return Ok{};
}

Result<Scene> Loader::build_scene() {
    LC_RETURN_IF_ERROR(validate_gltf_node_graph(nodes_, diagnostics_));
    Result<std::vector<int>> roots = gltf_scene_roots(nodes_, model_.defaultScene, diagnostics_);
    if (!roots) return roots.failure();
    LC_RETURN_IF_ERROR(read_gltf_materials(model_, diagnostics_, scene_));
    NodeReaders readers{GltfMeshReader(model_, diagnostics_, scene_),
                        GltfCameraReader(model_, nodes_, diagnostics_),
                        GltfLightReader(nodes_, diagnostics_)};
    LC_RETURN_IF_ERROR(traverse(*roots, readers));
    // The scene has all it needs from the table: a million light nodes'
    // records go before the GUID checks and the scene GUID allocate theirs.
    nodes_ = GltfNodeTable{};
    LC_RETURN_IF_ERROR(check_unique_light_guids(scene_.lights, diagnostics_));
    LC_RETURN_IF_ERROR(read_environment());
    scene_.source = path_;
    update_scene_bounds(scene_);
    readers.cameras.finish(scene_);
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
                                     std::vector<std::string>& warnings, const GltfLoadOptions& options) {
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

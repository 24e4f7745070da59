#pragma once
// Loads a glTF 2.0 scene (.gltf or .glb) with KHR_lights_punctual into a
// world-space Scene. Broken files give an lc::Error naming the problem.
//
// Conventions:
// - One Scene::Mesh per triangle primitive instance, flattened to world space;
//   normals go through the inverse transpose and are generated (area-weighted)
//   when the file has none. Triangle strips and fans become lists; points and
//   lines are skipped with a warning.
// - The scene drawn is `scene` when present, else scenes[0], else every root node.
// - Lights: position and -Z direction of the node's world transform. A light's
//   GUID is `extras.lightcuts_guid` on its node when present (the writer puts it
//   there so GUIDs survive edits), else derived from the light's index and name
//   and the node path. `extras: {"lightcuts_classic": true}` on the light or the
//   node marks a classic light.
// - Cameras (perspective only): eye at the node, looking down its -Z, up its +Y.
// - An environment map or a sun and sky named in the asset's extras
//   (gltf_environment.h) becomes Scene::environment.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "lightcuts/scene.h"
#include "lightcuts/result.h"

namespace lc::client {

// Extras keys we read and write.
inline constexpr const char* kClassicExtrasKey = "lightcuts_classic";
inline constexpr const char* kGuidExtrasKey = "lightcuts_guid";

struct GltfLoadOptions {
    // Buffer and image URIs are data: URIs or regular files inside the scene's
    // folder (gltf_resource_access.h); this also allows any other regular file
    // (absolute paths, "../"). FIFOs and devices are never read.
    bool allow_external_resources = false;
    // Nodes, scenes and punctual lights read by simdjson
    // (gltf_node_reader.h); false: tinygltf reads the whole file, as the
    // reference the fast path is tested against.
    bool stream_nodes = true;
};

// Warnings (skipped primitives, unsupported features) go to the log.
Result<Scene> load_scene(const std::filesystem::path& path, const GltfLoadOptions& options = {});
// Same, collecting the warnings instead of logging them.
Result<Scene> load_scene(const std::filesystem::path& path, std::vector<std::string>& warnings,
                         const GltfLoadOptions& options = {});
// A .gltf or .glb held in memory (fuzzing, tests). `resource_folder` stands
// for the scene's folder; empty: only data: URIs and GLB chunks, no file read.
Result<Scene> load_scene_from_memory(std::span<const uint8_t> bytes,
                                     const std::filesystem::path& resource_folder,
                                     std::vector<std::string>& warnings,
                                     const GltfLoadOptions& options = {});

// Recomputes Scene::bounds_min/max from the meshes and the positioned lights
// (directional lights have no position). An empty scene gets zero bounds.
void update_scene_bounds(Scene& scene);

}  // namespace lc::client

#pragma once
// KHR_lights_punctual lights -> SceneLights, one per node that names a
// light. Type, colour, intensity, range and spot cone are checked; the
// node's world transform gives the position and the direction (-Z). A
// light's GUID is the node's extras.lightcuts_guid when present, else derived
// from the light's index and name and the node's path from its root, so it
// is stable for a given file. extras.lightcuts_classic on the light or the
// node marks a classic light. GUIDs must be unique across the scene.
#include <glm/mat4x4.hpp>

#include <cstdint>
#include <span>
#include <string>

#include "editor_client/scene/gltf_diagnostics.h"
#include "editor_client/scene/gltf_node_table.h"
#include "lightcuts/result.h"
#include "lightcuts/scene.h"

namespace lc::client {

class GltfLightReader {
public:
    // Both outlive the reader.
    GltfLightReader(const GltfNodeTable& table, GltfDiagnostics& diagnostics)
        : table_(table), diagnostics_(diagnostics) {}

    // The light of node `node_index` (whose light is not kNone) at `world`;
    // `path_hash` stands for the path of nodes from its root.
    Result<SceneLight> read(int node_index, const glm::dmat4& world, uint64_t path_hash) const;

private:
    Result<int> light_index_of(const GltfNode& node, const std::string& node_what) const;
    Status read_emission(const GltfPunctualLight& in, const std::string& what, SceneLight& light) const;
    Status read_spot_cone(const GltfPunctualLight& in, const std::string& what, SceneLight& light) const;
    Status place(const glm::dmat4& world, const std::string& node_what, const std::string& what,
                 SceneLight& light) const;
    bool classic_flag(ExtrasFlag flag, const std::string& what) const;

    const GltfNodeTable& table_;
    GltfDiagnostics& diagnostics_;
};

// The first pair of lights (in light order) sharing a GUID, as an error.
Status check_unique_light_guids(std::span<const SceneLight> lights, const GltfDiagnostics& diagnostics);

}  // namespace lc::client

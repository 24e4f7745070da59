#pragma once
// glTF cameras -> Scene::cameras. Perspective cameras only (others are
// skipped with a warning, as are a yfov outside (0, pi) and a degenerate
// transform): the eye at the node, looking down its -Z, up its +Y. A camera
// without a name takes its node's. Its target, which only fixes the
// direction, is placed once the scene's bounds are known (finish()).
#include <tiny_gltf.h>

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <vector>

#include "editor_client/scene/gltf_diagnostics.h"
#include "editor_client/scene/gltf_node_table.h"
#include "lightcuts/result.h"
#include "lightcuts/scene.h"

namespace lc::client {

class GltfCameraReader {
public:
    // The three outlive the reader; `table` is read by add() only.
    GltfCameraReader(const tinygltf::Model& model, const GltfNodeTable& table, GltfDiagnostics& diagnostics)
        : model_(model), table_(table), diagnostics_(diagnostics) {}

    // Node `node_index`'s camera `camera_index` at `world`, into `scene`; a
    // camera the file does not have is an error.
    Status add(int node_index, int camera_index, const glm::dmat4& world, Scene& scene);
    // Each camera's target at the distance of the scene's centre (its bounds
    // are final), so that orbiting around it feels natural.
    void finish(Scene& scene) const;

private:
    const tinygltf::Model& model_;
    const GltfNodeTable& table_;
    GltfDiagnostics& diagnostics_;
    std::vector<glm::dvec3> forward_;  // per Scene::cameras entry, for finish()
};

}  // namespace lc::client

#pragma once
// What the render and view commands resolve before rendering: the light tree
// (from a dump, a bake on a server, or none) and the camera.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "editor_client/bake/bake_client.h"
#include "editor_client/render/settings/render_settings.h"
#include "lightcuts/scene.h"
#include "lightcuts/tree/light_tree.h"
#include "lightcuts/result.h"

namespace lc::client {

struct TreeSource {
    std::filesystem::path dump;             // --tree TREE.lcut
    std::optional<BakeClientOptions> bake;  // --server / --spawn-server

    bool empty() const { return dump.empty() && !bake; }
    std::string describe() const;
};

// Null when the source is empty. A dump must hold a Lightcuts result channel;
// a bake sends the scene's non-classic lights.
Result<std::shared_ptr<const LightTree>> obtain_tree(const Scene& scene, const TreeSource& source);

// --camera text wins, then --camera-index, then the file's first camera, then
// a camera framing the scene bounds.
Result<RenderCamera> choose_camera(const Scene& scene, const std::string& camera_text,
                                   std::optional<int> camera_index, float aspect);

}  // namespace lc::client

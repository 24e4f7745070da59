#include "editor_client/render/render_inputs.h"

#include "editor_client/bake/tree_store.h"
#include "editor_client/scene/surface_geometry.h"

namespace lc::client {

std::string TreeSource::describe() const {
    if (!dump.empty()) return "dump " + dump.string();
    if (bake) return bake->spawn_server ? "bake on a spawned server" : "bake on " + bake->server;
    return "none";
}

Result<std::shared_ptr<const LightTree>> obtain_tree(const Scene& scene, const TreeSource& source) {
    if (!source.dump.empty() && source.bake)
        return make_error("give either --tree or a server to bake on, not both");
    TreeStore store;
    if (!source.dump.empty()) {
        Status imported = store.import_dump(source.dump);
        if (!imported) return make_error(source.dump.string() + ": " + imported.error());
        return store.current();
    }
    if (source.bake) {
        BakeClientOptions bake = *source.bake;
        bake.geometry = geometry_the_bake_needs(scene, bake.indirect.method);
        Status imported = store.import(bake_lights(scene.lights, scene.guid, bake));
        if (!imported) return make_error("bake failed: " + imported.error());
        return store.current();
    }
    return std::shared_ptr<const LightTree>();
}

Result<RenderCamera> choose_camera(const Scene& scene, const std::string& camera_text,
                                   std::optional<int> camera_index, float aspect) {
    if (!camera_text.empty()) {
        if (camera_index) return make_error("give either --camera or --camera-index, not both");
        return parse_camera(camera_text);
    }
    if (camera_index) {
        if (*camera_index < 0 || size_t(*camera_index) >= scene.cameras.size())
            return make_error("--camera-index " + std::to_string(*camera_index) +
                              " is out of range: the scene has " +
                              std::to_string(scene.cameras.size()) + " camera(s)");
        return camera_from_scene(scene.cameras[size_t(*camera_index)]);
    }
    if (!scene.cameras.empty()) return camera_from_scene(scene.cameras.front());
    return frame_scene_bounds(scene, aspect);
}

}  // namespace lc::client

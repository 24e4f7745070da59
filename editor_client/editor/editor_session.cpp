#include "editor_client/editor/editor_session.h"

#include <utility>

#include "editor_client/render/render_inputs.h"

namespace lc::client {

namespace {

// The scene's own camera, else one framing its bounds.
RenderCamera first_camera(const Scene& scene, float aspect) {
    Result<RenderCamera> camera = choose_camera(scene, "", std::nullopt, aspect);
    return camera ? camera.value() : frame_scene_bounds(scene, aspect);
}

}  // namespace

EditorSession::EditorSession(Scene scene, EditorSessionOptions options)
    : edits_(std::move(scene)),
      view_(first_camera(edits_.scene(), options.aspect)),
      baking_(std::move(options.bake), options.spawned_server_threads) {}

}  // namespace lc::client

#pragma once
// Keeps the renderer's lights and tree in step with the editor's session: the
// renderer reads the scene's lights only when its tree is set, so every edit
// or import re-sets it. A tree baked for other lights is not shown: until the
// next bake the view renders the edited lights in reference mode instead.
#include <cstdint>
#include <memory>

#include "editor_client/editor/editor_session.h"
#include "editor_client/render/renderer.h"
#include "lightcuts/result.h"

namespace lc::client {

class RendererSync {
public:
    RendererSync(Renderer& renderer, const EditorSession& session) : renderer_(renderer), session_(session) {}

    Status update();
    // Counts the renderer's lights and tree changing (a progressive image starts again).
    uint64_t updates() const { return updates_; }
    // Whether the renderer holds the session's lights and tree (no edit since update()).
    bool in_step() const {
        return synced_ && revision_ == session_.scene_revision() && generation_ == session_.baking().tree_generation();
    }

    // The session's settings at a size, falling back to reference mode while
    // there is no tree matching the lights.
    RenderSettings settings(uint32_t width, uint32_t height) const {
        return render_settings_for(session_.view(), width, height, renderer_.has_tree());
    }

private:
    Renderer& renderer_;
    const EditorSession& session_;
    std::shared_ptr<const LightTree> tree_;  // what the GPU holds a copy of
    uint64_t revision_ = 0;
    uint64_t generation_ = 0;
    bool synced_ = false;
    uint64_t updates_ = 0;
};

}  // namespace lc::client

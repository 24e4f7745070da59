#include "editor_client/window/renderer_sync.h"

#include <optional>

#include "lightcuts/tree/gpu_layout.h"
#include "lightcuts/status_macros.h"

namespace lc::client {

Status RendererSync::update() {
    if (in_step()) return Ok{};
    tree_ = session_.tree_matches_scene() ? session_.baking().tree() : nullptr;
    if (tree_ && tree_->empty()) tree_.reset();
    // The walk form lives only while the renderer copies it to the GPU.
    std::optional<WalkTree> walk;
    if (tree_) {
        Result<WalkTree> made = make_walk_tree(*tree_);
        if (!made) return make_error("light tree: " + made.error());
        walk = std::move(made).value();
    }
    LC_RETURN_IF_ERROR(renderer_.set_tree(walk ? &*walk : nullptr));
    revision_ = session_.scene_revision();
    generation_ = session_.baking().tree_generation();
    synced_ = true;
    ++updates_;
    return Ok{};
}

}  // namespace lc::client

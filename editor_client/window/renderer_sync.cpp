#include "editor_client/window/renderer_sync.h"

#include "lightcuts/status_macros.h"

namespace lc::client {

Status RendererSync::update() {
    if (in_step()) return Ok{};
    tree_ = session_.tree_matches_scene() ? session_.tree() : nullptr;
    if (tree_ && tree_->empty()) tree_.reset();
    LC_RETURN_IF_ERROR(renderer_.set_tree(tree_.get()));
    revision_ = session_.scene_revision();
    generation_ = session_.tree_generation();
    synced_ = true;
    ++updates_;
    return Ok{};
}

}  // namespace lc::client

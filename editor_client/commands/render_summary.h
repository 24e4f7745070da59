#pragma once
// What `render` prints after the frame: the indirect light's census, the
// heap's and the loop limit's shortfalls, the error and the summary line.
#include <cstdint>
#include <optional>

#include "editor_client/commands/render_options.h"
#include "editor_client/commands/render_request.h"
#include "editor_client/render/output/render_stats.h"
#include "editor_client/render/render_inputs.h"
#include "lightcuts/scene.h"

namespace lc::client {

// The imported tree as the renderer and the CPU evaluator both walk it, and
// the one fact of the imported form the walk form does not keep.
struct RenderTree {
    std::optional<WalkTree> walk;  // none without a tree source
    uint32_t deepest_vpl_bounce = 0;

    const WalkTree* get() const { return walk ? &*walk : nullptr; }
};


// What the tree's indirect light is, or why there is none, in a line.
void print_indirect_census(const RenderStats& stats, const Scene& scene, const TreeSource& source,
                           const RenderTree& tree);

// The loop limit's and the heap's shortfalls, the error against the reference, and the summary line.
void print_report(const RenderStats& stats, const RenderOptions& options, const RenderRequest& request,
                  double command_ms);

}  // namespace lc::client

#pragma once
// The text of the editor's overlay: frame time, cut sizes, light count, tree
// state and the last bake. Kept apart from ImGui so it is tested as text.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "editor_client/editor/editor_session.h"

namespace lc::client {

// Where the progressive view's image stands.
struct RefinementProgress {
    uint32_t pass = 0;      // passes done
    uint32_t passes = 1;
    double percent = 100.0;  // of the refining pass's tiles
    uint32_t divisor = 1;    // of the refining pass
    bool complete() const { return pass >= passes; }
};

// What the last frame measured (from the renderer's stats and timestamps).
struct FrameInfo {
    double frame_ms = 0.0;  // wall time of the last frame
    double gpu_ms = 0.0;    // GPU time of the last frame
    uint32_t width = 0;     // rendered size (reduced while moving)
    uint32_t height = 0;
    uint32_t divisor = 1;           // 1: full resolution
    std::optional<double> avg_cut;  // absent in reference mode or before a read-back
    std::optional<uint32_t> max_cut;
    std::optional<RefinementProgress> refinement;  // progressive view only
    std::optional<uint32_t> realtime_frames;       // real-time mode: frames in its history
    uint64_t loop_limit_stops = 0;  // pixels the device's loop limit cut short (said, not hidden)
};

std::vector<std::string> overlay_lines(const EditorSession& session, const FrameInfo& frame);

}  // namespace lc::client

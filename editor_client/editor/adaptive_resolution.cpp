#include "editor_client/editor/adaptive_resolution.h"

#include <algorithm>
#include <cmath>

namespace lc::client {

uint32_t AdaptiveResolution::next_divisor(bool view_changed, double now_ms) {
    if (view_changed) last_change_ms_ = now_ms;
    const bool settled = now_ms - last_change_ms_ >= options_.settle_ms;
    if (settled || full_frame_ms_ <= 0.0) {
        divisor_ = 1;
        return divisor_;
    }
    divisor_ = divisor_meeting_target();
    return divisor_;
}

uint32_t AdaptiveResolution::divisor_meeting_target() const {
    if (full_frame_ms_ <= 0.0) return std::max(options_.max_divisor, 1u);
    uint32_t d = 1;
    while (d < options_.max_divisor && full_frame_ms_ / double(d * d) > options_.target_frame_ms)
        ++d;
    return d;
}

void AdaptiveResolution::report_frame(uint32_t divisor, double frame_ms) {
    if (!std::isfinite(frame_ms) || frame_ms < 0.0 || divisor == 0) return;
    const double full = frame_ms * double(divisor) * double(divisor);
    // Smoothed, so one slow frame does not drop the resolution at once.
    full_frame_ms_ = full_frame_ms_ <= 0.0 ? full : 0.7 * full_frame_ms_ + 0.3 * full;
}

}  // namespace lc::client

#pragma once
// Reduced resolution while the camera moves, full resolution once it stops:
// the editor stays interactive with thousands of lights on a software
// rasteriser, and the still image is always the exact full-size one.
// The cost model is per pixel: a frame at divisor d costs about full / d^2.
#include <cstdint>

namespace lc::client {

struct AdaptiveResolutionOptions {
    double target_frame_ms = 100.0;  // moving frames aim at this (10 fps)
    double settle_ms = 200.0;        // still this long: render at full size
    uint32_t max_divisor = 8;        // at most 1/8 of the width and height
};

class AdaptiveResolution {
public:
    explicit AdaptiveResolution(AdaptiveResolutionOptions options = {}) : options_(options) {}

    // Call before each frame: whether the view changed this frame, and a clock
    // in milliseconds. Returns the divisor of the full width and height.
    uint32_t next_divisor(bool view_changed, double now_ms);
    // Call after each frame with its measured time at the divisor it used.
    void report_frame(uint32_t divisor, double frame_ms);

    uint32_t divisor() const { return divisor_; }
    // The smallest divisor whose estimated frame meets the target (the largest
    // allowed before any frame was reported): the progressive editor's first pass.
    uint32_t divisor_meeting_target() const;
    // Estimated full-resolution frame time (0 until a frame was reported).
    double full_frame_ms() const { return full_frame_ms_; }

private:
    AdaptiveResolutionOptions options_;
    uint32_t divisor_ = 1;
    double full_frame_ms_ = 0.0;
    double last_change_ms_ = -1e300;
};

// max(1, size / divisor), rounded up so no pixel column is lost.
inline uint32_t reduced_size(uint32_t size, uint32_t divisor) {
    if (divisor <= 1) return size;
    const uint32_t reduced = (size + divisor - 1) / divisor;
    return reduced == 0 ? 1 : reduced;
}

}  // namespace lc::client

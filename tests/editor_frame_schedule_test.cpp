// The editor loop's scheduling step (editor/frame_schedule.h) without a window
// or a GPU: whole frames at a reduced size while the camera moves, the
// progressive view's tiles from the coarse pass to the full size with its
// start, restart and completion events, and the real-time mode's whole frames.
// GPU and frame times are fed in as fixed numbers, as the loop would measure them.
#include "editor_client/editor/frame_schedule.h"

#include <gtest/gtest.h>

#include <optional>

namespace lc::client {
namespace {

RenderSettings view_settings(uint32_t width, uint32_t height, RenderMode mode = RenderMode::kLightcuts) {
    RenderSettings settings;
    settings.mode = mode;
    settings.width = width;
    settings.height = height;
    return settings;
}

FrameScheduleOptions progressive_options() {
    FrameScheduleOptions options;
    options.width = 64;
    options.height = 48;
    options.progressive = true;
    options.refinement.frame_budget_ms = 30.0;
    options.refinement.tile_size = 16;
    options.tile_alignment = 8;
    return options;
}

// A frame as the editor loop runs it: plan, the tiles' GPU time, the frame's time.
struct Frame {
    FramePlan plan;
    FrameInfo info;
};

Frame run_frame(FrameSchedule& schedule, const FrameInputs& inputs, double gpu_ms_per_pixel = 0.01) {
    Frame frame;
    frame.plan = schedule.plan(inputs);
    frame.info.frame_ms = 5.0;
    schedule.finish_frame(frame.plan, frame.info, inputs.frame, inputs.now_ms);
    if (frame.plan.batch)
        schedule.report_gpu(frame.plan, gpu_ms_per_pixel * double(frame.plan.batch->pixels()));
    return frame;
}

TEST(EditorFrameSchedule, WholeFramesShrinkWhileTheCameraMovesAndReturnToFullSize) {
    FrameScheduleOptions options;
    options.width = 160;
    options.height = 120;
    FrameSchedule schedule(options);
    FrameInputs inputs;
    inputs.settings = view_settings(160, 120);

    // Nothing measured yet: full size, even while moving.
    inputs.moved = true;
    FramePlan first = schedule.plan(inputs);
    EXPECT_FALSE(first.tiled);
    EXPECT_EQ(first.divisor, 1u);
    EXPECT_EQ(first.settings.width, 160u);
    FrameInfo info;
    info.frame_ms = 800.0;  // a full frame of 800 ms: 1/3 of each side meets the 100 ms target
    schedule.finish_frame(first, info, 0, 0.0);
    EXPECT_FALSE(info.refinement) << "whole frames have no refinement progress";

    inputs.frame = 1;
    inputs.now_ms = 10.0;
    const FramePlan moving = schedule.plan(inputs);
    EXPECT_EQ(moving.divisor, 3u);
    EXPECT_EQ(moving.settings.width, 54u);  // rounded up: no pixel column lost
    EXPECT_EQ(moving.settings.height, 40u);
    EXPECT_TRUE(schedule.whole_image(first));
    EXPECT_FALSE(schedule.whole_image(moving));

    // Still for the settle time: full size again.
    inputs.moved = false;
    inputs.now_ms = 10.0 + options.adaptive.settle_ms;
    const FramePlan settled = schedule.plan(inputs);
    EXPECT_EQ(settled.divisor, 1u);
    EXPECT_EQ(settled.settings, inputs.settings);
    EXPECT_TRUE(schedule.events().empty());

    // Without adaptive resolution every frame is full size.
    options.adaptive_resolution = false;
    FrameSchedule fixed(options);
    fixed.finish_frame(first, info, 0, 0.0);
    inputs.moved = true;
    EXPECT_EQ(fixed.plan(inputs).divisor, 1u);
}

TEST(EditorFrameSchedule, AProgressiveImageRefinesCoarseThenFullAndCompletesOnce) {
    FrameSchedule schedule(progressive_options());
    FrameInputs inputs;
    inputs.settings = view_settings(64, 48);
    inputs.renderer_updates = 1;

    Frame frame = run_frame(schedule, inputs);
    ASSERT_TRUE(frame.plan.tiled);
    ASSERT_TRUE(frame.plan.batch);
    ASSERT_EQ(schedule.events().size(), 1u);
    EXPECT_EQ(schedule.events()[0].kind, RefinementEvent::Kind::kStarted);
    // Nothing measured: the coarse pass is the coarsest the adaptive resolution allows.
    EXPECT_EQ(frame.plan.divisor, 8u);
    EXPECT_EQ(frame.plan.settings.width, 8u);
    EXPECT_EQ(frame.plan.settings.height, 6u);
    EXPECT_TRUE(frame.plan.batch->new_image);
    EXPECT_TRUE(schedule.whole_image(frame.plan)) << "the coarse pass is one tile";
    ASSERT_TRUE(frame.info.refinement);
    EXPECT_EQ(frame.info.refinement->pass, 1u);
    EXPECT_EQ(frame.info.refinement->passes, 2u);
    EXPECT_TRUE(schedule.refining());

    uint32_t full_size_frames = 0;
    while (frame.plan.batch) {
        ++inputs.frame;
        inputs.now_ms += 10.0;
        frame = run_frame(schedule, inputs);
        if (frame.plan.batch) {
            EXPECT_EQ(frame.plan.divisor, 1u);
            EXPECT_EQ(frame.plan.settings.width, 64u);
            EXPECT_FALSE(frame.plan.batch->tiles.empty());
            ++full_size_frames;
        }
        ASSERT_LT(inputs.frame, 100u) << "the refinement never completed";
    }
    // 64x48 in 16-pixel tiles is 12 tiles; 0.01 ms a pixel fits 11 of them in 30 ms, so two frames.
    EXPECT_EQ(full_size_frames, 2u);
    ASSERT_EQ(schedule.events().size(), 2u);
    EXPECT_EQ(schedule.events()[1].kind, RefinementEvent::Kind::kCompleted);
    EXPECT_EQ(schedule.events()[1].frame, inputs.frame - 1);
    EXPECT_DOUBLE_EQ(schedule.first_complete_seconds().value(), (inputs.now_ms - 10.0) / 1000.0);
    EXPECT_EQ(schedule.refining_frames(), 3u);
    EXPECT_FALSE(schedule.refining());
    EXPECT_TRUE(schedule.refined_for(inputs.settings, 1));

    // Complete: the next frames take no tiles, and say so.
    EXPECT_TRUE(frame.plan.tiled);
    ASSERT_TRUE(frame.info.refinement);
    EXPECT_TRUE(frame.info.refinement->complete());
    EXPECT_EQ(schedule.refining_frames(), 3u);
    EXPECT_EQ(schedule.events().size(), 2u) << "completed once";
}

TEST(EditorFrameSchedule, ChangedSettingsLightsOrALostImageRestartTheRefinement) {
    FrameSchedule schedule(progressive_options());
    FrameInputs inputs;
    inputs.settings = view_settings(64, 48);
    run_frame(schedule, inputs);
    inputs.frame = 1;
    run_frame(schedule, inputs);  // the first full-size tiles
    ASSERT_EQ(schedule.events().size(), 1u);

    // The error ratio changes while the full-size pass refines.
    inputs.frame = 2;
    inputs.now_ms = 250.0;
    inputs.settings.error_ratio = 0.05f;
    const Frame restarted = run_frame(schedule, inputs);
    ASSERT_EQ(schedule.events().size(), 2u);
    const RefinementEvent& event = schedule.events()[1];
    EXPECT_EQ(event.kind, RefinementEvent::Kind::kRestarted);
    EXPECT_EQ(event.frame, 2u);
    EXPECT_DOUBLE_EQ(event.seconds, 0.25);
    EXPECT_EQ(event.pass, 1u);
    EXPECT_EQ(event.passes, 2u);
    EXPECT_GT(event.percent, 0.0);
    EXPECT_LT(event.percent, 100.0);
    ASSERT_TRUE(restarted.plan.batch);
    EXPECT_TRUE(restarted.plan.batch->new_image);
    EXPECT_EQ(restarted.plan.batch->pass, 0u);

    // The same settings again: no restart.
    inputs.frame = 3;
    run_frame(schedule, inputs);
    EXPECT_EQ(schedule.events().size(), 2u);
    // The renderer's lights or tree changed; a screenshot overwrote the image.
    inputs.frame = 4;
    inputs.renderer_updates = 2;
    run_frame(schedule, inputs);
    EXPECT_EQ(schedule.events().size(), 3u);
    inputs.frame = 5;
    inputs.image_lost = true;
    run_frame(schedule, inputs);
    EXPECT_EQ(schedule.events().size(), 4u);
    EXPECT_EQ(schedule.events().back().kind, RefinementEvent::Kind::kRestarted);

    // Auto-exposure tone-maps the refining image again: the image is the same one.
    inputs.frame = 6;
    inputs.image_lost = false;
    inputs.settings.exposure = 0.25f;
    schedule.set_refined_exposure(0.25f);
    run_frame(schedule, inputs);
    EXPECT_EQ(schedule.events().size(), 4u);
    EXPECT_FALSE(schedule.refined_for(inputs.settings, 2)) << "still refining";
}

TEST(EditorFrameSchedule, TheRealtimeModeRendersWholeFullSizeFramesWithoutTiles) {
    FrameSchedule schedule(progressive_options());
    FrameInputs inputs;
    inputs.settings = view_settings(64, 48, RenderMode::kRealtime);
    inputs.moved = true;
    EXPECT_FALSE(schedule.tiled(inputs.settings));
    const Frame frame = run_frame(schedule, inputs);
    EXPECT_TRUE(frame.plan.realtime);
    EXPECT_FALSE(frame.plan.tiled);
    EXPECT_FALSE(frame.plan.batch);
    EXPECT_EQ(frame.plan.divisor, 1u);
    EXPECT_EQ(frame.plan.settings, inputs.settings);
    EXPECT_FALSE(frame.info.refinement);
    EXPECT_TRUE(schedule.events().empty()) << "no progressive image was started";
    EXPECT_TRUE(schedule.whole_image(frame.plan));

    // Back to lightcuts: the progressive image starts.
    inputs.settings.mode = RenderMode::kLightcuts;
    EXPECT_TRUE(schedule.tiled(inputs.settings));
    run_frame(schedule, inputs);
    ASSERT_EQ(schedule.events().size(), 1u);
    EXPECT_EQ(schedule.events()[0].kind, RefinementEvent::Kind::kStarted);
}

TEST(EditorFrameSchedule, EventNames) {
    EXPECT_STREQ(refinement_event_name(RefinementEvent::Kind::kStarted), "started");
    EXPECT_STREQ(refinement_event_name(RefinementEvent::Kind::kRestarted), "restarted");
    EXPECT_STREQ(refinement_event_name(RefinementEvent::Kind::kCompleted), "completed");
}

}  // namespace
}  // namespace lc::client

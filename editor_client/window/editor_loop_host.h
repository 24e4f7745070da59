#pragma once
// The editor loop's side of the script and panel commands that need the
// renderer (editor_loop.h). Screenshots render the current state afresh at
// full size, so a scripted screenshot right after an edit shows the edit (not
// the last, possibly reduced, frame); called between frames, when the GPU is
// idle. With a progressive view, saving the view saves the image as refined so
// far, and a screenshot that overwrote an unfinished image asks for a restart.
#include <cstdint>
#include <filesystem>
#include <utility>

#include "editor_client/editor/frame_schedule.h"
#include "editor_client/editor/script_runner.h"
#include "editor_client/render/renderer.h"
#include "editor_client/window/renderer_sync.h"
#include "lightcuts/result.h"

namespace lc::client {

// The renderer's last image: a PFM of the linear radiance, or a PNG of what is shown.
Status write_rendered_image(const Renderer& renderer, const std::filesystem::path& path);

class EditorLoopHost final : public EditorHost {
public:
    EditorLoopHost(Renderer& renderer, RendererSync& sync, uint32_t width, uint32_t height,
                   const FrameSchedule& schedule)
        : renderer_(renderer), sync_(sync), width_(width), height_(height), schedule_(schedule) {}

    Status screenshot(const std::filesystem::path& path) override;
    Status save_view(const std::filesystem::path& path) override;
    // Refined for what the next frame would show: a setting or light changed
    // since the image completed (the loop restarts it next frame) is not.
    // The real-time mode's view is refined once its history has outgrown the spatial filter.
    bool view_refined() const override;
    void request_quit() override { quit_ = true; }

    bool quit_requested() const { return quit_; }
    uint32_t count() const { return count_; }
    // Whether a screenshot replaced the renderer's unfinished image (once).
    bool take_image_lost() { return std::exchange(image_lost_, false); }

private:
    Renderer& renderer_;
    RendererSync& sync_;
    uint32_t width_, height_;
    const FrameSchedule& schedule_;
    bool quit_ = false;
    bool image_lost_ = false;
    uint32_t count_ = 0;
};

}  // namespace lc::client

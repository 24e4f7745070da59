#include "editor_client/window/editor_loop_host.h"

#include <system_error>
#include <vector>

#include "editor_client/render/output/image_io.h"
#include "editor_client/render/passes/temporal_history.h"
#include "lightcuts/status_macros.h"

namespace lc::client {

Status write_rendered_image(const Renderer& renderer, const std::filesystem::path& path) {
    std::error_code ec;
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
    if (path.extension() == ".pfm") {
        Result<std::vector<float>> hdr = renderer.read_hdr();
        if (!hdr) return make_error(hdr.error());
        FloatImage image{renderer.width(), renderer.height(), {}};
        image.rgb.reserve(hdr->size() / 4 * 3);
        for (size_t i = 0; i < hdr->size(); i += 4)
            image.rgb.insert(image.rgb.end(), &(*hdr)[i], &(*hdr)[i + 3]);
        return write_pfm(path, image);
    }
    Result<std::vector<uint8_t>> pixels = renderer.read_display();
    if (!pixels) return make_error(pixels.error());
    return write_png(path, renderer.width(), renderer.height(), *pixels);
}

Status EditorLoopHost::screenshot(const std::filesystem::path& path) {
    if (path.empty()) return make_error("screenshot needs a file name");
    LC_RETURN_IF_ERROR(sync_.update());
    Result<RenderStats> rendered = renderer_.render(sync_.settings(width_, height_));
    if (!rendered) return make_error("screenshot: " + rendered.error());
    if (schedule_.refining()) image_lost_ = true;
    if (Status written = write_rendered_image(renderer_, path); !written)
        return make_error("screenshot: " + written.error());
    ++count_;
    return Ok{};
}

Status EditorLoopHost::save_view(const std::filesystem::path& path) {
    if (!schedule_.progressive()) return screenshot(path);
    if (path.empty()) return make_error("save-view needs a file name");
    if (Status written = write_rendered_image(renderer_, path); !written)
        return make_error("save-view: " + written.error());
    return Ok{};
}

bool EditorLoopHost::view_refined() const {
    const RenderSettings settings = sync_.settings(width_, height_);
    if (settings.mode == RenderMode::kRealtime)
        return sync_.in_step() && renderer_.realtime_frames() >= kRealtimeRefinedFrames;
    if (settings.mode == RenderMode::kRestir)
        return sync_.in_step() && renderer_.restir_frames() >= kRealtimeRefinedFrames;
    if (!schedule_.progressive()) return true;
    return sync_.in_step() && schedule_.refined_for(settings, sync_.updates());
}

}  // namespace lc::client

#include "editor_client/report/progress_display.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>

namespace lc::client {

ProgressDisplay::ProgressDisplay(std::FILE* out) : out_(out), terminal_(::isatty(::fileno(out)) != 0) {}

void ProgressDisplay::update(const std::string& stage, double percent) {
    if (!std::isfinite(percent)) percent = 0.0;
    percent = std::clamp(percent, 0.0, 100.0);
    if (terminal_) {
        constexpr int kWidth = 30;
        int filled = static_cast<int>(percent / 100.0 * kWidth + 0.5);
        std::string bar(static_cast<size_t>(filled), '#');
        bar.resize(kWidth, '.');
        std::fprintf(out_, "\r[%s] %5.1f%% %-24s", bar.c_str(), percent, stage.c_str());
        std::fflush(out_);
        drawn_ = true;
        return;
    }
    int decile = static_cast<int>(percent / 10.0);
    if (stage == stage_ && decile == last_decile_) return;
    stage_ = stage;
    last_decile_ = decile;
    std::fprintf(out_, "progress: %s %.0f%%\n", stage.c_str(), percent);
    std::fflush(out_);
}

void ProgressDisplay::finish() {
    if (terminal_ && drawn_) std::fprintf(out_, "\n");
    drawn_ = false;
}

}  // namespace lc::client

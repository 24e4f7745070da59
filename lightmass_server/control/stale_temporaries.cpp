#include "lightmass_server/control/stale_temporaries.h"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <charconv>
#include <fstream>

namespace lc::bake {
namespace fs = std::filesystem;
namespace {

constexpr std::string_view kJobPrefix = "lightmass-bake-";
constexpr std::string_view kTmpMarker = ".tmp-";

// The number at the start of `digits`, when it is followed by '-' and more digits.
std::optional<pid_t> pid_before_counter(std::string_view digits) {
    pid_t pid = 0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), pid);
    if (ec != std::errc() || pid <= 0 || end == digits.data() + digits.size() || *end != '-')
        return std::nullopt;
    std::string_view counter(end + 1, size_t(digits.data() + digits.size() - end - 1));
    if (counter.ends_with(".lcut")) counter.remove_suffix(5);
    if (counter.empty() || counter.find_first_not_of("0123456789") != std::string_view::npos)
        return std::nullopt;
    return pid;
}

bool is_stale(pid_t owner) {
    if (owner == getpid()) return true;
    return kill(owner, 0) != 0 && errno == ESRCH;
}

}  // namespace

std::optional<pid_t> temporary_owner(const std::string& file_name) {
    const std::string_view name = file_name;
    if (name.starts_with(kJobPrefix)) return pid_before_counter(name.substr(kJobPrefix.size()));
    const size_t marker = name.rfind(kTmpMarker);
    if (marker == std::string_view::npos || marker == 0) return std::nullopt;
    return pid_before_counter(name.substr(marker + kTmpMarker.size()));
}

SweepReport sweep_stale_temporaries(const std::vector<fs::path>& dirs) {
    SweepReport report;
    for (const fs::path& dir : dirs) {
        std::error_code ec;
        if (dir.empty() || !fs::is_directory(dir, ec)) continue;
        for (const fs::directory_entry& entry : fs::directory_iterator(dir, ec)) {
            const std::optional<pid_t> owner = temporary_owner(entry.path().filename().string());
            if (!owner || !is_stale(*owner)) continue;
            std::error_code removed;
            fs::remove_all(entry.path(), removed);
            if (removed)
                report.errors.push_back(entry.path().string() + ": " + removed.message());
            else
                report.removed.push_back(entry.path());
        }
        if (ec) report.errors.push_back(dir.string() + ": " + ec.message());
    }
    return report;
}

bool write_file_whole(const fs::path& path, const std::string& text) {
    static std::atomic<uint64_t> counter{0};
    fs::path tmp = path;
    tmp += std::string(kTmpMarker) + std::to_string(getpid()) + "-" + std::to_string(counter++);
    {
        std::ofstream file(tmp, std::ios::binary | std::ios::trunc);
        file.write(text.data(), std::streamsize(text.size()));
        if (!file.flush()) {
            std::error_code ignored;
            fs::remove(tmp, ignored);
            return false;
        }
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) fs::remove(tmp, ec);
    return !ec;
}

}  // namespace lc::bake

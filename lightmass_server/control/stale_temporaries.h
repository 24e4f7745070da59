#pragma once
// What a crashed (or SIGKILLed) server leaves behind, and the startup sweep
// that removes it. Everything the server writes is complete or temporary:
// recordings are written as NAME.tmp-PID-N and renamed when whole
// (protocol/dump.h), the radiosity PLY likewise, and a multi-rank bake's job
// folder lightmass-bake-PID-N (with its tree, lightmass-bake-PID-N.lcut) is a
// temporary as a whole, removed when the bake ends. A temporary whose PID is
// not a running process, or is this process (a restart keeps its PID), is stale.
#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace lc::bake {

// The PID in a temporary's name, when it is one of ours.
std::optional<pid_t> temporary_owner(const std::string& file_name);

struct SweepReport {
    std::vector<std::filesystem::path> removed;
    std::vector<std::string> errors;  // what could not be removed, and why
};

// Removes the stale temporaries directly inside each of `dirs` (missing ones are skipped).
SweepReport sweep_stale_temporaries(const std::vector<std::filesystem::path>& dirs);

// Writes `text` to `path` through a sibling temporary renamed over it when whole.
bool write_file_whole(const std::filesystem::path& path, const std::string& text);

}  // namespace lc::bake

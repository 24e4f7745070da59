#pragma once
// The files between the server and an MPI bake's rank 0 (docs/ARCHITECTURE.md,
// "Bakes over MPI ranks"). The server writes a job folder: request.msg (the
// bake's settings as an encoded BakeRequest message), lights.scene,
// geometry.geom and environment.env (the same channel encodings the client
// sent, so the ranks validate them as the server does). Rank 0 writes
// progress (a line "percent stage", replaced atomically), then either
// result.lcut (the tree as the result channel) with report.txt, or error.txt.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "lightcuts/environment.h"
#include "lightcuts/result.h"
#include "lightcuts/scene_geometry.h"
#include "lightcuts/scene_light.h"
#include "lightmass_server/bake/bake_pipeline.h"
#include "protocol/messages.h"

namespace lc::bake {

// The job's files as bytes: what rank 0 broadcasts to the other ranks.
struct RankJobBytes {
    std::vector<uint8_t> request, lights, geometry, environment;  // empty: absent
};

// The job decoded: what every rank bakes from.
struct RankJob {
    BakeRequestMsg request;
    std::vector<SceneLight> lights;
    std::optional<SceneGeometry> geometry;
    std::optional<Environment> environment;
};

// The bake's inputs as the job's files' bytes, for `ranks` ranks.
RankJobBytes encode_rank_job(const BakeInputs& inputs, uint32_t ranks);
Status write_rank_job(const std::filesystem::path& dir, const RankJobBytes& job);
Result<RankJobBytes> read_rank_job(const std::filesystem::path& dir);
Result<RankJob> decode_rank_job(const RankJobBytes& bytes);
// The options a bake of this job runs with, as the session would set them.
BuildOptions job_build_options(const BakeRequestMsg& request);

// Rank 0's answer. Lines of report.txt: "effect TEXT", "warning TEXT",
// "build_ms X", "pairing_cost X", "pairing_lower_bound X", "exact 0|1",
// "levels N", "depth N", "rank R lights N bytes_sent B peak_rss_kb K".
Status write_rank_result(const std::filesystem::path& dir, const BuildResult& result,
                         const std::vector<std::string>& rank_lines);
// report.txt alone, for a tree the ranks wrote into result.lcut themselves.
Status write_rank_report(const std::filesystem::path& dir, const BuildReport& report,
                         const std::vector<std::string>& rank_lines);
// The tree stays on disk: `tree_file` (rank 0's result.lcut, moved out of the
// job folder) is validated and adopted as the result's channel_file.
Result<BuildResult> read_rank_result(const std::filesystem::path& dir,
                                     const std::filesystem::path& tree_file);
Status write_rank_error(const std::filesystem::path& dir, const std::string& text);
Status write_rank_progress(const std::filesystem::path& dir, std::string_view stage, double percent);

// Whole-file helpers (a missing file reads as an error naming it).
Result<std::vector<uint8_t>> read_file_bytes(const std::filesystem::path& path);
Status write_file_atomically(const std::filesystem::path& path, std::span<const uint8_t> bytes);

}  // namespace lc::bake

#include "lightmass_server/mpi/rank/split_lbvh.h"

#include <fcntl.h>
#include <mpi.h>
#include <tbb/parallel_for.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>

#include "lightcuts/status_macros.h"
#include "lightmass_server/builders/build_phase_timer.h"
#include "lightmass_server/mpi/lbvh_top.h"
#include "lightmass_server/mpi/lbvh_units.h"
#include "lightmass_server/mpi/rank/mpi_transfer.h"
#include "protocol/channel_records.h"

namespace lc::bake {
namespace {

namespace fs = std::filesystem;

// The largest unit: small enough that one merge's scratch (about 500 bytes a
// light) stays well under a rank's share, large enough that the top stays small.
uint32_t unit_limit(uint64_t total, int ranks) {
    return uint32_t(std::clamp<uint64_t>(total / (16 * uint64_t(ranks)), 64, uint64_t{1} << 18));
}

// Every rank's first and last keys; each rank takes its nearest non-empty neighbours'.
ShareNeighbours exchange_boundaries(const SortedShare& share, int rank, int ranks) {
    struct Boundary {
        uint64_t has, first_group, last_group, first_code, last_code;
    };
    Boundary mine{!share.keys.empty(), 0, 0, 0, 0};
    if (mine.has) {
        while (share.group_begin[mine.first_group + 1] == 0) ++mine.first_group;
        mine.last_group = kLightGroupCount - 1;
        while (share.group_begin[mine.last_group] == share.keys.size()) --mine.last_group;
        mine.first_code = share.keys.front().code;
        mine.last_code = share.keys.back().code;
    }
    std::vector<Boundary> all(static_cast<size_t>(ranks));
    MPI_Allgather(&mine, sizeof mine, MPI_BYTE, all.data(), sizeof mine, MPI_BYTE, MPI_COMM_WORLD);
    ShareNeighbours near;
    for (int r = rank - 1; r >= 0 && !near.has_before; --r) {
        if (!all[size_t(r)].has) continue;
        near =
            ShareNeighbours{true, false, uint32_t(all[size_t(r)].last_group), 0, all[size_t(r)].last_code, 0};
    }
    for (int r = rank + 1; r < ranks && !near.has_after; ++r) {
        if (!all[size_t(r)].has) continue;
        near.has_after = true;
        near.after_group = uint32_t(all[size_t(r)].first_group);
        near.after_code = all[size_t(r)].first_code;
    }
    return near;
}

// Rank 0: the channel file at its full size with its count; the records follow.
Result<int> create_channel_file(const fs::path& path, uint32_t node_count) {
    const int fd = ::open(path.c_str(), O_CREAT | O_TRUNC | O_WRONLY | O_CLOEXEC, 0644);
    if (fd < 0) return make_error("cannot create " + path.string() + ": " + std::strerror(errno));
    const std::vector<uint8_t> prefix = encode_result_prefix(node_count);
    const off_t size = off_t(prefix.size() + uint64_t(node_count) * result_record_bytes());
    if (::pwrite(fd, prefix.data(), prefix.size(), 0) != ssize_t(prefix.size()) ||
        ::ftruncate(fd, size) != 0) {
        ::close(fd);
        return make_error("cannot size " + path.string() + ": " + std::strerror(errno));
    }
    return fd;
}

// Rank 0 scatters each rank its units' bases (their counts known from the gather).
std::vector<uint32_t> scatter_bases(const std::vector<uint32_t>& all, const std::vector<int>& per_rank) {
    std::vector<int> at(per_rank.size(), 0);
    for (size_t r = 1; r < per_rank.size(); ++r) at[r] = at[r - 1] + per_rank[r - 1];
    int mine = 0;
    MPI_Scatter(per_rank.data(), 1, MPI_INT, &mine, 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::vector<uint32_t> bases(size_t(mine), 0);
    MPI_Scatterv(all.data(), per_rank.data(), at.data(), MPI_UINT32_T, bases.data(), mine, MPI_UINT32_T, 0,
                 MPI_COMM_WORLD);
    return bases;
}

// This rank's units' records, into the file rank 0 made, units on several
// threads (each writes its own records); each unit's root's representative's index.
Result<std::vector<int32_t>> write_units(const fs::path& path, const SortedShare& share,
                                         const std::vector<LbvhUnit>& units,
                                         const std::vector<uint32_t>& bases) {
    std::vector<size_t> base_at{0};
    for (const LbvhUnit& unit : units) base_at.push_back(base_at.back() + unit.level_counts.size());
    if (base_at.back() != bases.size())
        return make_error("rank 0 sent " + std::to_string(bases.size()) + " bases for " +
                          std::to_string(base_at.back()));
    const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC);
    if (fd < 0) return make_error("cannot open " + path.string() + ": " + std::strerror(errno));
    std::vector<Result<int32_t>> written(units.size(), int32_t{-1});
    tbb::parallel_for(size_t{0}, units.size(), [&](size_t u) {
        written[u] = write_unit_records(fd, share, units[u],
                                        std::span(bases).subspan(base_at[u], base_at[u + 1] - base_at[u]));
    });
    std::vector<int32_t> representatives;
    for (Result<int32_t>& unit : written) {
        if (!unit || *unit < 0) {
            ::close(fd);
            return unit ? make_error("a unit's representative has no index") : unit.failure();
        }
        representatives.push_back(*unit);
    }
    if (::close(fd) != 0) return make_error("cannot close " + path.string() + ": " + std::strerror(errno));
    return representatives;
}

}  // namespace

namespace {

struct MergedShare {
    SortedShare share;
    std::vector<LbvhUnit> units;
};

// Spread, then merge this rank's units; rank 0 gets every unit's summary and depths.
Result<MergedShare> merge_share(OwnedLights mine, const BuildOptions& options, int rank, int ranks,
                                const ProgressFn& say, RankStats& stats) {
    say("spreading the lights by space", 5.0);
    Result<SortedShare> share = spread_by_space(std::move(mine), stats.bytes_sent);
    if (!share) return share.failure();
    if (share->total_lights > kMaxSceneLights)
        return make_error("too large: " + std::to_string(share->total_lights) +
                              " lights for one tree (limit " + std::to_string(kMaxSceneLights) + ")",
                          ErrorKind::kRefused);
    const ShareNeighbours near = exchange_boundaries(*share, rank, ranks);
    say("merging each rank's subtrees", 30.0);
    Result<std::vector<LbvhUnit>> units =
        merge_units(*share, near, unit_limit(share->total_lights, ranks), options);
    if (!units) return units.failure();
    return MergedShare{std::move(share.value()), std::move(units.value())};
}

// Rank 0's close: the top's records, then the file takes its name.
Status finish_channel_file(int fd, const LbvhTop& top, const std::vector<int32_t>& representatives,
                           const fs::path& partial, const fs::path& tree_file) {
    Status written = write_top_records(fd, top, representatives);
    if (::close(fd) != 0 && written)
        written = make_error("cannot close " + partial.string() + ": " + std::strerror(errno));
    if (!written) return written;
    std::error_code ec;
    fs::rename(partial, tree_file, ec);
    if (ec) return make_error("cannot rename " + partial.string() + ": " + ec.message());
    return Ok{};
}

}  // namespace

Result<BuildReport> build_split_lbvh(OwnedLights mine, const BuildOptions& options, const fs::path& tree_file,
                                     const ProgressFn& progress, RankStats& stats) {
    const auto start = std::chrono::steady_clock::now();
    BuildReport report;
    BuildPhaseTimer timer(report);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    const std::string stage = "lbvh over " + std::to_string(ranks) + " ranks: ";
    const ProgressFn say = [&](std::string_view what, double percent) {
        return !progress || progress(stage + std::string(what), percent);
    };
    Result<MergedShare> merged = merge_share(std::move(mine), options, rank, ranks, say, stats);
    if (!merged) return merged.failure();
    timer.lap("spread and merge");
    std::vector<UnitSummary> summaries;
    std::vector<uint32_t> depths;
    for (const LbvhUnit& unit : merged->units) {
        summaries.push_back(summarize_unit(merged->share, unit));
        depths.insert(depths.end(), unit.level_counts.begin(), unit.level_counts.end());
    }
    Result<std::vector<UnitSummary>> all_units = gather_in_rank_order(summaries, stats.bytes_sent);
    Result<std::vector<uint32_t>> all_depths = gather_in_rank_order(depths, stats.bytes_sent);
    if (!all_units || !all_depths) return make_error("cannot gather the ranks' subtrees");
    std::vector<int> depths_per_rank(size_t(ranks), 0);
    const int my_depths = int(depths.size());
    MPI_Gather(&my_depths, 1, MPI_INT, depths_per_rank.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);

    const fs::path partial = tree_file.string() + ".partial";
    LbvhTop top;
    int fd = -1;
    if (rank == 0) {
        say("the top over " + std::to_string(all_units->size()) + " subtrees", 70.0);
        Result<LbvhTop> built = build_lbvh_top(*all_units, *all_depths, options);
        if (!built) return built.failure();
        top = std::move(built.value());
        Result<int> created = create_channel_file(partial, top.node_count);
        if (!created) return created.failure();
        fd = *created;
        say("writing the records on every rank", 80.0);
    }
    timer.lap("gather and top");
    const std::vector<uint32_t> bases = scatter_bases(top.bases, depths_per_rank);
    Result<std::vector<int32_t>> representatives = write_units(partial, merged->share, merged->units, bases);
    if (!representatives) return representatives.failure();
    Result<std::vector<int32_t>> all_representatives =
        gather_in_rank_order(*representatives, stats.bytes_sent);
    if (!all_representatives) return all_representatives.failure();
    timer.lap("records");
    if (rank != 0) return BuildReport{};
    LC_RETURN_IF_ERROR(finish_channel_file(fd, top, *all_representatives, partial, tree_file));
    timer.lap("top records");
    report.depth = top.depth;
    report.build_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    stats.tree_written = true;
    return report;
}

}  // namespace lc::bake

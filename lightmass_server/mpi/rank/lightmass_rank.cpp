// lightmass_rank: one MPI rank of a bake that lightmass_server launched with
// `mpirun -n N lightmass_rank --job DIR` (mpi/rank_bake_launcher.h). Rank 0
// reads the job folder and broadcasts it; every rank bakes its share
// (rank_bake.h); rank 0 writes the tree, the report and progress back into the
// folder, or error.txt. Any failure aborts the whole job, so no rank waits forever.
#include <mpi.h>
#include <sys/resource.h>

#include <CLI/CLI.hpp>

#include <chrono>
#include <csignal>
#include <cstdio>
#include <string>
#include <thread>

#include "lightcuts/version.h"
#include "lightmass_server/mpi/rank/mpi_transfer.h"
#include "lightmass_server/mpi/rank/rank_bake.h"

namespace {

using namespace lc;
using namespace lc::bake;
namespace fs = std::filesystem;

struct RankFlags {
    fs::path job;
    int die_rank = -1;   // tests: this rank kills itself once the job has arrived
    bool stall = false;  // tests: every rank waits forever once the job has arrived
};

[[noreturn]] void fail(int rank, const fs::path& dir, const std::string& text) {
    std::fprintf(stderr, "lightmass_rank %d: %s\n", rank, text.c_str());
    if (rank == 0) (void)write_rank_error(dir, text);
    MPI_Abort(MPI_COMM_WORLD, 3);
    std::abort();
}

Result<RankJob> receive_job(int rank, const fs::path& dir) {
    RankJobBytes bytes;
    if (rank == 0) {
        Result<RankJobBytes> read = read_rank_job(dir);
        // An unreadable job still broadcasts (empty), so the other ranks fail too.
        if (read)
            bytes = std::move(read.value());
        else
            std::fprintf(stderr, "lightmass_rank 0: %s\n", read.error().c_str());
    }
    for (std::vector<uint8_t>* part : {&bytes.request, &bytes.lights, &bytes.geometry, &bytes.environment})
        broadcast_bytes(*part);
    return decode_rank_job(bytes);
}

// Rank 0's progress into the job folder, at most every 100 ms.
ProgressFn progress_into(const fs::path& dir) {
    auto last = std::make_shared<std::chrono::steady_clock::time_point>();
    return [dir, last](std::string_view stage, double percent) {
        const auto now = std::chrono::steady_clock::now();
        if (now - *last >= std::chrono::milliseconds(100) || percent >= 100.0) {
            *last = now;
            (void)write_rank_progress(dir, stage, percent);
        }
        return true;
    };
}

// "rank R lights N bytes_sent B peak_rss_kb K" for every rank, on rank 0.
std::vector<std::string> rank_lines(int rank, int ranks, const RankStats& stats) {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    const uint64_t mine[3] = {stats.lights_made, stats.bytes_sent, uint64_t(usage.ru_maxrss)};
    std::vector<uint64_t> all(size_t(3 * ranks));
    MPI_Gather(mine, 3, MPI_UINT64_T, all.data(), 3, MPI_UINT64_T, 0, MPI_COMM_WORLD);
    std::vector<std::string> lines;
    for (int r = 0; rank == 0 && r < ranks; ++r) {
        const uint64_t* s = &all[size_t(3 * r)];
        lines.push_back("rank " + std::to_string(r) + " lights " + std::to_string(s[0]) + " bytes_sent " +
                        std::to_string(s[1]) + " peak_rss_kb " + std::to_string(s[2]));
    }
    return lines;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"lightmass_rank: one MPI rank of a lightmass_server bake"};
    app.set_version_flag("--version", std::string("lightmass_rank ") + lc::kVersion);
    RankFlags flags;
    app.add_option("--job", flags.job, "The bake's job folder, written by lightmass_server")->required();
    app.add_option("--test-die-rank", flags.die_rank, "Tests: this rank dies once the job has arrived");
    app.add_flag("--test-stall", flags.stall, "Tests: every rank stalls once the job has arrived");
    CLI11_PARSE(app, argc, argv);

    MPI_Init(&argc, &argv);
    int rank = 0, ranks = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &ranks);
    // MPI_Init returned on every rank: every host answered (the server's --mpi-launch-seconds).
    if (rank == 0) (void)write_rank_progress(flags.job, "ranks started", 0.0);
    Result<RankJob> job = receive_job(rank, flags.job);
    if (!job) fail(rank, flags.job, "bad job: " + job.error());
    const ProgressFn progress = rank == 0 ? progress_into(flags.job) : ProgressFn{};
    if (progress) progress("job received by " + std::to_string(ranks) + " ranks", 0.0);
    if (rank == flags.die_rank) std::raise(SIGKILL);
    while (flags.stall) std::this_thread::sleep_for(std::chrono::seconds(1));

    RankStats stats;
    Result<std::optional<BuildResult>> baked =
        bake_share(*job, rank, ranks, flags.job / "result.lcut", progress, stats);
    if (!baked) fail(rank, flags.job, baked.error());
    const std::vector<std::string> lines = rank_lines(rank, ranks, stats);
    if (rank == 0) {
        Status written = stats.tree_written ? write_rank_report(flags.job, (*baked)->report, lines)
                                            : write_rank_result(flags.job, **baked, lines);
        if (!written) fail(rank, flags.job, written.error());
    }
    MPI_Finalize();
    return 0;
}

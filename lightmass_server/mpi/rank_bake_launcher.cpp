#include "lightmass_server/mpi/rank_bake_launcher.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <optional>
#include <span>
#include <sstream>
#include <thread>

#include "lightmass_server/mpi/host_roster.h"
#include "lightmass_server/mpi/job_log_faults.h"
#include "lightmass_server/mpi/local_slots.h"
#include "lightmass_server/mpi/mpi_failure.h"
#include "lightmass_server/mpi/rank_job.h"

namespace lc::bake {
namespace fs = std::filesystem;
namespace {

constexpr auto kPollInterval = std::chrono::milliseconds(50);
// After SIGTERM, mpirun takes its ranks down; past this, the group gets SIGKILL.
constexpr auto kTerminateGrace = std::chrono::seconds(5);

// Beside the server (the build tree), else where the package installs it:
// PREFIX/libexec/lightcuts/ for PREFIX/bin/lightmass_server (CMakeLists.txt install()).
fs::path rank_program(const MpiLaunchOptions& mpi) {
    if (!mpi.rank_program.empty()) return mpi.rank_program;
    std::error_code ec;
    const fs::path self = fs::read_symlink("/proc/self/exe", ec);
    if (ec) return "lightmass_rank";
    const fs::path beside = self.parent_path() / "lightmass_rank";
    const fs::path installed = self.parent_path().parent_path() / "libexec" / "lightcuts" / "lightmass_rank";
    return fs::exists(beside, ec) || !fs::exists(installed, ec) ? beside : installed;
}

fs::path make_job_dir(const MpiLaunchOptions& mpi) {
    static std::atomic<uint64_t> counter{0};
    std::error_code ec;
    const fs::path root = mpi.work_dir.empty() ? fs::temp_directory_path(ec) : mpi.work_dir;
    return root / ("lightmass-bake-" + std::to_string(getpid()) + "-" + std::to_string(++counter));
}

std::vector<std::string> launch_command(const MpiLaunchOptions& mpi, uint32_t ranks, const fs::path& hostfile,
                                        const fs::path& dir, const LocalLaunch& local) {
    std::vector<std::string> argv{mpi.launcher, "-n", std::to_string(ranks)};
    argv.insert(argv.end(), local.extra_args.begin(), local.extra_args.end());
    argv.insert(argv.end(), mpi.launcher_args.begin(), mpi.launcher_args.end());
    if (!hostfile.empty()) argv.insert(argv.end(), {"--hostfile", hostfile.string()});
    argv.insert(argv.end(), {rank_program(mpi).string(), "--job", dir.string()});
    argv.insert(argv.end(), mpi.rank_args.begin(), mpi.rank_args.end());
    return argv;
}

// The host file this job runs on: the server's, less the hosts that earlier
// bakes lost (host_roster.h), written into the job folder.
Result<fs::path> job_hostfile(const MpiLaunchOptions& mpi, const fs::path& dir) {
    if (mpi.hostfile.empty() || !mpi.lost_hosts) return mpi.hostfile;
    Result<std::string> kept = mpi.lost_hosts->hostfile_without_lost(mpi.hostfile);
    if (!kept) return kept.failure();
    const fs::path path = dir / "hosts";
    Status written =
        write_file_atomically(path, std::span(reinterpret_cast<const uint8_t*>(kept->data()), kept->size()));
    if (!written) return written.failure();
    return path;
}

// "a, b" from a host file's lines, or this machine when there is none.
std::string hosts_named_in(const fs::path& hostfile) {
    if (hostfile.empty()) return "this machine";
    std::ifstream in(hostfile);
    std::string hosts;
    for (std::string line; std::getline(in, line);) {
        const std::string host = host_of_hostfile_line(line);
        if (!host.empty()) hosts += (hosts.empty() ? "" : ", ") + host;
    }
    return hosts;
}

// The server's environment for the launcher, plus the Open MPI settings that
// make a bake over several machines fail fast and clearly, where the user set
// none: TCP keepalives between mpirun and its daemons that notice a silent
// host in about 5 s (the default's take 8 minutes: 300 s idle, then 9 probes
// 20 s apart), and daemons left attached to their remote shell, so that a
// daemon's own error (it cannot connect back) reaches mpirun's log instead of
// leaving mpirun waiting. An `--mpi-arg=--mca` of the same name still wins.
std::vector<std::string> launcher_environment() {
    std::vector<std::string> env;
    for (char** entry = environ; *entry != nullptr; ++entry) env.emplace_back(*entry);
    constexpr std::pair<const char*, const char*> kDefaults[] = {
        {"OMPI_MCA_oob_tcp_keepalive_time", "2"},
        {"OMPI_MCA_oob_tcp_keepalive_intvl", "1"},
        {"OMPI_MCA_oob_tcp_keepalive_probes", "3"},
        {"OMPI_MCA_orte_leave_session_attached", "1"}};
    for (const auto& [name, value] : kDefaults)
        if (std::getenv(name) == nullptr) env.push_back(std::string(name) + "=" + value);
    return env;
}

std::vector<char*> pointers_to(const std::vector<std::string>& strings) {
    std::vector<char*> pointers;
    for (const std::string& s : strings) pointers.push_back(const_cast<char*>(s.c_str()));
    pointers.push_back(nullptr);
    return pointers;
}

// Starts argv in a new process group (its id is the child's pid), its output
// into `log`. posix_spawn: the server has threads, so no code runs after a fork.
Result<pid_t> spawn_group(const std::vector<std::string>& argv, const fs::path& log) {
    std::vector<char*> args = pointers_to(argv);
    const std::vector<std::string> env_strings = launcher_environment();
    std::vector<char*> env = pointers_to(env_strings);
    posix_spawn_file_actions_t files;
    posix_spawn_file_actions_init(&files);
    posix_spawn_file_actions_addopen(&files, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_adddup2(&files, 1, 2);
    posix_spawnattr_t attributes;
    posix_spawnattr_init(&attributes);
    posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
    posix_spawnattr_setpgroup(&attributes, 0);
    pid_t pid = 0;
    const int failed = posix_spawnp(&pid, args[0], &files, &attributes, args.data(), env.data());
    posix_spawn_file_actions_destroy(&files);
    posix_spawnattr_destroy(&attributes);
    if (failed != 0)
        return make_error("cannot start the MPI launcher '" + argv[0] + "': " + std::strerror(failed));
    return pid;
}

std::string text_of(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string tail_of(const fs::path& path, size_t bytes) {
    const std::string text = text_of(path);
    return text.size() > bytes ? "..." + text.substr(text.size() - bytes) : text;
}

// Forwards rank 0's latest progress line; false when the bake is cancelled.
bool forward_progress(const fs::path& dir, const ProgressFn& progress, std::string& last) {
    if (!progress) return true;
    std::ifstream in(dir / "progress");
    std::string line;
    if (in && std::getline(in, line) && line != last) last = line;
    const size_t space = last.find(' ');
    if (space == std::string::npos) return progress("mpi: starting ranks", 0.0);
    return progress("mpi: " + last.substr(space + 1), std::atof(last.substr(0, space).c_str()));
}

// Signals the whole group, then waits; SIGKILL to the group if it lingers.
void stop_group(pid_t pid) {
    kill(-pid, SIGTERM);
    const auto deadline = std::chrono::steady_clock::now() + kTerminateGrace;
    int status = 0;
    while (waitpid(pid, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() > deadline) {
            kill(-pid, SIGKILL);
            waitpid(pid, &status, 0);
            break;
        }
        std::this_thread::sleep_for(kPollInterval);
    }
    kill(-pid, SIGKILL);  // whatever of the group outlived mpirun
}

std::string exit_text(int status) {
    if (WIFEXITED(status)) return "exited with status " + std::to_string(WEXITSTATUS(status));
    if (WIFSIGNALED(status)) return "was killed by signal " + std::to_string(WTERMSIG(status));
    return "ended abnormally";
}

std::string over_ranks(uint32_t ranks) {
    return "MPI bake over " + std::to_string(ranks) + " ranks";
}

// A fault that mpirun's log pins on a host: one line naming it; a host that
// stopped answering is left out of this server's next bakes.
Error host_fault_error(const MpiLaunchOptions& mpi, uint32_t ranks, const HostFault& fault) {
    std::string text = over_ranks(ranks) + " failed: " + fault.text;
    if (fault.host_lost && mpi.lost_hosts) {
        mpi.lost_hosts->mark_lost(fault.host);
        const auto minutes = std::chrono::duration_cast<std::chrono::minutes>(mpi.lost_hosts->pause());
        text += "; this server leaves it out of its bakes for the next " + std::to_string(minutes.count()) +
                " minutes";
    }
    return make_error(text);
}

// Why a job that ended without a tree failed: a lost host first (its ranks
// died with it), then rank 0's own error, then a rank killed on a host, then the log.
Error job_failure(const MpiLaunchOptions& mpi, uint32_t ranks, const std::vector<std::string>& argv,
                  int status, const fs::path& dir) {
    const std::optional<HostFault> fault = host_fault_in_log(text_of(dir / "mpirun.log"));
    if (fault && fault->host_lost) return host_fault_error(mpi, ranks, *fault);
    if (fs::exists(dir / "error.txt"))
        return make_error("MPI bake failed: " + tail_of(dir / "error.txt", 2000));
    if (fault) return host_fault_error(mpi, ranks, *fault);
    // The launcher's whole output for the operator (info: a spawned --quiet server keeps it off the
    // user's terminal); a refusal we know reaches the client as one line naming the flag.
    const std::string log = tail_of(dir / "mpirun.log", 4000);
    spdlog::info("MPI job of {} ranks failed; {} said: {}", ranks, argv[0], log);
    if (std::string known = explain_mpi_failure(log, ranks); !known.empty()) return make_error(known);
    const std::string code =
        WIFEXITED(status) && WEXITSTATUS(status) == 127 ? " (launcher '" + argv[0] + "' not found?)" : "";
    return make_error(over_ranks(ranks) + " failed: " + argv[0] + " " + exit_text(status) + code +
                      " (a rank died or could not start); its log: " + tail_of(dir / "mpirun.log", 1500));
}

// No rank started within --mpi-launch-seconds: a host never answered.
Error launch_timeout(const MpiLaunchOptions& mpi, uint32_t ranks, const fs::path& hostfile,
                     const fs::path& dir) {
    const std::optional<HostFault> fault = host_fault_in_log(text_of(dir / "mpirun.log"));
    if (fault) return host_fault_error(mpi, ranks, *fault);
    return make_error(
        over_ranks(ranks) + " failed: its ranks had not all started after " +
        std::to_string(mpi.launch_seconds) +
        " s (--mpi-launch-seconds): a host did not answer; the job's hosts: " + hosts_named_in(hostfile));
}

Result<BuildResult> run_job(const BakeInputs& inputs, const fs::path& dir, const ProgressFn& progress) {
    Status written = write_rank_job(dir, encode_rank_job(inputs, inputs.ranks));
    if (!written) return make_error("MPI job: " + written.error());
    Result<fs::path> hostfile = job_hostfile(inputs.mpi, dir);
    if (!hostfile)
        return make_error(over_ranks(inputs.ranks) + " refused: " + hostfile.error(), ErrorKind::kRefused);
    const LocalLaunch local = local_launch(inputs.mpi, inputs.ranks, std::max(1u, std::thread::hardware_concurrency()));
    if (!local.note.empty()) spdlog::info("{}", local.note);
    const std::vector<std::string> argv = launch_command(inputs.mpi, inputs.ranks, *hostfile, dir, local);
    Result<pid_t> pid = spawn_group(argv, dir / "mpirun.log");
    if (!pid) return pid.failure();
    const auto launch_deadline =
        std::chrono::steady_clock::now() + std::chrono::seconds(inputs.mpi.launch_seconds);
    bool started = false;
    std::string last_progress;
    int status = 0;
    const BakeStop* stop = inputs.stop.get();
    while (waitpid(*pid, &status, WNOHANG) == 0) {
        // The bake's own stop (Cancel, disconnect, --max-bake-seconds) ends the job even without a
        // progress callback to ask.
        const bool stopped = stop_requested(stop);
        if (stopped || !forward_progress(dir, progress, last_progress)) {
            stop_group(*pid);
            const std::string job = "the MPI job of " + std::to_string(inputs.ranks) + " ranks";
            if (stop && stop->requested()) return stop->reason(job);
            return make_error("cancelled: " + job + " was stopped", ErrorKind::kCancelled);
        }
        // Rank 0 writes its first progress once MPI_Init has returned on every rank.
        started = started || fs::exists(dir / "progress");
        if (!started && std::chrono::steady_clock::now() > launch_deadline) {
            stop_group(*pid);
            return launch_timeout(inputs.mpi, inputs.ranks, *hostfile, dir);
        }
        std::this_thread::sleep_for(kPollInterval);
    }
    kill(-*pid, SIGKILL);  // no rank outlives its job
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !fs::exists(dir / "result.lcut"))
        return job_failure(inputs.mpi, inputs.ranks, argv, status, dir);
    // The tree leaves the job folder (removed when the bake ends) and is streamed from its own file.
    const fs::path tree_file = dir.string() + ".lcut";
    std::error_code ec;
    if (inputs.mpi.keep_job_dirs)
        fs::copy_file(dir / "result.lcut", tree_file, fs::copy_options::overwrite_existing, ec);
    else
        fs::rename(dir / "result.lcut", tree_file, ec);
    if (ec) return make_error("cannot move rank 0's tree out of " + dir.string() + ": " + ec.message());
    Result<BuildResult> result = read_rank_result(dir, tree_file);
    if (result && !local.note.empty()) result->report.effects.push_back(local.note);
    return result;
}

}  // namespace

Result<BuildResult> run_bake_on_ranks(const BakeInputs& inputs, const ProgressFn& progress) {
    const MpiLaunchOptions& mpi = inputs.mpi;
    if (inputs.ranks > mpi.max_ranks) {
        return make_error("the bake asks for " + std::to_string(inputs.ranks) +
                              " MPI ranks; this server allows at most " + std::to_string(mpi.max_ranks) +
                              " (lightmass_server --mpi-max-ranks)",
                          ErrorKind::kRefused);
    }
    const fs::path dir = make_job_dir(mpi);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) return make_error("cannot make the MPI job folder " + dir.string() + ": " + ec.message());
    Result<BuildResult> result = run_job(inputs, dir, progress);
    if (!mpi.keep_job_dirs) fs::remove_all(dir, ec);
    return result;
}

}  // namespace lc::bake

#include "editor_client/bake/server_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <thread>
#include <vector>

extern char** environ;

namespace lc::client {

std::string locate_server_binary() {
    if (const char* env = std::getenv("LC_SERVER_BIN"); env && *env) return env;
    std::error_code ec;
    auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
    if (ec) return "lightmass_server";
    return (self.parent_path() / "lightmass_server").string();
}

std::vector<std::string> spawned_server_flags(uint32_t ranks, const std::vector<std::string>& server_args) {
    std::vector<std::string> flags;
    // The server's default allows 16 ranks; a bigger bake raises it for the server it starts.
    if (ranks > 16) flags.push_back("--mpi-max-ranks=" + std::to_string(ranks));
    flags.insert(flags.end(), server_args.begin(), server_args.end());
    return flags;
}

Result<std::unique_ptr<ServerProcess>> ServerProcess::spawn(unsigned threads,
                                                           const std::vector<std::string>& server_flags) {
    std::vector<std::string> args{"--listen", "127.0.0.1:0", "--threads", std::to_string(threads), "--quiet"};
    args.insert(args.end(), server_flags.begin(), server_flags.end());
    return spawn_with(locate_server_binary(), args);
}

Result<std::unique_ptr<ServerProcess>> ServerProcess::spawn_with(const std::string& binary,
                                                                  const std::vector<std::string>& extra_args) {
    if (::access(binary.c_str(), X_OK) != 0)
        return make_error("cannot run the bake server '" + binary + "' (set LC_SERVER_BIN or build lightmass_server)");
    int pipe_fds[2];
    if (::pipe2(pipe_fds, O_CLOEXEC) != 0) return make_error("pipe() failed");

    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, pipe_fds[1], STDOUT_FILENO);
    std::vector<std::string> args = {binary};
    args.insert(args.end(), extra_args.begin(), extra_args.end());
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    pid_t pid = 0;
    int rc = ::posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    ::close(pipe_fds[1]);
    if (rc != 0) {
        ::close(pipe_fds[0]);
        return make_error("cannot start the bake server '" + binary + "'");
    }

    // Read the first line, "listening on HOST:PORT", with a deadline.
    std::string line;
    auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (line.find('\n') == std::string::npos) {
        auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) break;
        pollfd pfd{pipe_fds[0], POLLIN, 0};
        if (::poll(&pfd, 1, static_cast<int>(left.count())) <= 0) break;
        char buffer[256];
        ssize_t n = ::read(pipe_fds[0], buffer, sizeof buffer);
        if (n <= 0) break;
        line.append(buffer, static_cast<size_t>(n));
    }
    ::close(pipe_fds[0]);
    const std::string prefix = "listening on ";
    size_t at = line.find(prefix);
    size_t end = line.find('\n');
    if (at == std::string::npos || end == std::string::npos) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, nullptr, 0);
        return make_error("the bake server did not report its address (got '" + line + "')");
    }
    std::string address = line.substr(at + prefix.size(), end - at - prefix.size());
    return std::unique_ptr<ServerProcess>(new ServerProcess(pid, address));
}

ServerProcess::~ServerProcess() { terminate(); }

int ServerProcess::terminate() {
    if (pid_ <= 0) return -1;
    pid_t pid = pid_;
    pid_ = -1;
    ::kill(pid, SIGTERM);
    int status = 0;
    for (int i = 0; i < 100; ++i) {  // up to 5 s for a clean exit
        if (::waitpid(pid, &status, WNOHANG) == pid) return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
    return -1;
}

}  // namespace lc::client

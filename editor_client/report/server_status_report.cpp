#include "editor_client/report/server_status_report.h"

#include <algorithm>
#include <cstdio>

namespace lc::client {
namespace {

double mib(uint64_t bytes) { return double(bytes) / double(1 << 20); }

uint64_t free_bytes(const StatusReplyMsg& status) {
    return status.memory_budget_bytes - std::min(status.memory_held_bytes, status.memory_budget_bytes);
}

std::string format(const char* pattern, auto... values) {
    char line[512];
    std::snprintf(line, sizeof line, pattern, values...);
    return line;
}

size_t count_state(const StatusReplyMsg& status, const std::string& state) {
    return size_t(std::count_if(status.bakes.begin(), status.bakes.end(),
                                [&](const BakeStatusEntry& b) { return b.state == state; }));
}

}  // namespace

std::string server_status_text(const StatusReplyMsg& s) {
    std::string text = s.version + ", up " + format("%.0f", s.uptime_seconds) + " s\n";
    text += format("connections: %u of %u\n", s.connections, s.max_connections);
    text += format("bakes: %zu running, %zu queued, %zu streaming; %u big bakes at once, each at most %u s\n",
                   count_state(s, "running"), count_state(s, "queued"), count_state(s, "streaming"),
                   s.max_concurrent_bakes, s.max_bake_seconds);
    for (const BakeStatusEntry& b : s.bakes) {
        const std::string ranks = b.ranks > 0 ? format(", %u ranks", b.ranks) : "";
        text += format("  connection %llu bake %u: %s, %s %.1f%%%s\n", (unsigned long long)b.connection, b.bake_id,
                       b.state.c_str(), b.stage.empty() ? "waiting" : b.stage.c_str(), b.percent, ranks.c_str());
    }
    text += format("memory budget: %.1f MiB held, %.1f MiB free of %.1f MiB\n", mib(s.memory_held_bytes),
                   mib(free_bytes(s)), mib(s.memory_budget_bytes));
    if (s.mpi_max_ranks == 0)
        text += "mpi: no bakes over ranks (--mpi-max-ranks 0)\n";
    else
        text += format("mpi: launcher '%s', up to %u ranks a bake\n", s.mpi_launcher.c_str(), s.mpi_max_ranks);
    return text;
}

nlohmann::json server_status_json(const StatusReplyMsg& s) {
    nlohmann::json bakes = nlohmann::json::array();
    for (const BakeStatusEntry& b : s.bakes)
        bakes.push_back({{"connection", b.connection}, {"bake_id", b.bake_id}, {"state", b.state},
                         {"stage", b.stage}, {"percent", b.percent}, {"ranks", b.ranks}});
    return {{"version", s.version},
            {"uptime_seconds", s.uptime_seconds},
            {"connections", s.connections},
            {"bakes", bakes},
            {"bakes_running", count_state(s, "running")},
            {"bakes_queued", count_state(s, "queued")},
            {"memory_budget_bytes", s.memory_budget_bytes},
            {"memory_held_bytes", s.memory_held_bytes},
            {"memory_free_bytes", free_bytes(s)},
            {"limits",
             {{"max_connections", s.max_connections},
              {"max_concurrent_bakes", s.max_concurrent_bakes},
              {"max_bake_seconds", s.max_bake_seconds}}},
            {"mpi", {{"launcher", s.mpi_launcher}, {"max_ranks", s.mpi_max_ranks}}}};
}

}  // namespace lc::client

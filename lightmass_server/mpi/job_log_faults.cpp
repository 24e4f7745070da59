#include "lightmass_server/mpi/job_log_faults.h"

#include <cctype>

namespace lc::bake {
namespace {

// The word after `label` (skipping blanks), or empty when the label is absent.
std::string word_after(std::string_view log, std::string_view label) {
    const size_t at = log.find(label);
    if (at == std::string_view::npos) return {};
    size_t begin = at + label.size();
    while (begin < log.size() && (log[begin] == ' ' || log[begin] == '\t')) ++begin;
    size_t end = begin;
    while (end < log.size() && !std::isspace(static_cast<unsigned char>(log[end]))) ++end;
    return std::string(log.substr(begin, end - begin));
}

// The rest of the line after `label`, without a trailing period.
std::string line_after(std::string_view log, std::string_view label) {
    const size_t at = log.find(label);
    if (at == std::string_view::npos) return {};
    const size_t begin = at + label.size();
    std::string line(log.substr(begin, log.find('\n', begin) - begin));
    while (!line.empty() && (line.back() == '.' || line.back() == '\r')) line.pop_back();
    return line;
}

std::string without_colon(std::string word) {
    if (!word.empty() && word.back() == ':') word.pop_back();
    return word;
}

// mpirun's "ORTE has lost communication with a remote daemon": the host went away mid-job.
std::optional<HostFault> lost_daemon(std::string_view log) {
    if (log.find("lost communication with a remote daemon") == std::string_view::npos) return {};
    const size_t remote = log.find("Remote daemon:");
    if (remote == std::string_view::npos) return {};
    const std::string host = word_after(log.substr(remote), "on node");
    if (host.empty()) return {};
    return HostFault{host,
                     "host " + host +
                         " stopped answering: Open MPI lost contact with its daemon there "
                         "(its network or the machine went down)",
                     true};
}

// A daemon that started on a host but could not reach mpirun: a firewall or the wrong network.
std::optional<HostFault> no_connection_back(std::string_view log) {
    const size_t at = log.find("unable to complete a TCP connection");
    if (at == std::string_view::npos) return {};
    const std::string host = word_after(log.substr(at), "Local host:");
    if (host.empty()) return {};
    const std::string peer = word_after(log.substr(at), "Remote host:");
    return HostFault{host,
                     "host " + host + " could not connect back to mpirun on " + (peer.empty() ? "?" : peer) +
                         " (a firewall, or the network given to oob_tcp_if_include, is in the way)",
                     true};
}

// ssh as Open MPI's remote shell could not reach the host at all.
std::optional<HostFault> ssh_failed(std::string_view log) {
    for (std::string_view label : {"ssh: connect to host ", "ssh: Could not resolve hostname "}) {
        const std::string host = without_colon(word_after(log, label));
        if (host.empty()) continue;
        std::string reason = line_after(log, label).substr(host.size());
        reason.erase(0, reason.find_first_not_of(": "));
        return HostFault{host, "host " + host + " did not answer ssh: " + reason, true};
    }
    return {};
}

// "mpirun noticed that process rank R with PID P on node HOST exited on signal N (Name)."
std::optional<HostFault> rank_killed(std::string_view log) {
    const size_t at = log.find("noticed that process rank ");
    if (at == std::string_view::npos) return {};
    const std::string_view notice = log.substr(at);
    const std::string rank = word_after(notice, "process rank");
    const std::string host = word_after(notice, "on node");
    if (host.empty()) return {};
    return HostFault{host, "rank " + rank + " on host " + host + line_after(notice, host), false};
}

}  // namespace

std::optional<HostFault> host_fault_in_log(std::string_view log) {
    // The host's own loss first: when a host goes, its ranks die too.
    for (auto reader : {lost_daemon, no_connection_back, ssh_failed, rank_killed}) {
        if (std::optional<HostFault> fault = reader(log)) return fault;
    }
    return std::nullopt;
}

}  // namespace lc::bake

// editor_client server-status HOST:PORT [--json] [--token-file F] [--tls [--tls-ca F]] [--timeout S]
// Asks a running lightmass_server how it is: version, uptime, bakes running
// and queued with their progress, memory budget held and free, limits, MPI.
#include <cstdio>
#include <iostream>
#include <memory>

#include "editor_client/bake/server_status.h"
#include "editor_client/commands/command_errors.h"
#include "editor_client/commands/commands.h"
#include "editor_client/report/server_status_report.h"

namespace lc::client {

void register_server_status_command(CLI::App& app) {
    struct Options {
        ServerStatusQuery query;
        bool json = false;
        bool timing = false;
    };
    auto options = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand("server-status", "Ask a lightmass_server how it is (bakes, memory, limits)");
    cmd->add_option("server", options->query.server, "HOST:PORT of the server")->required();
    cmd->add_flag("--json", options->json, "Print the status as JSON");
    cmd->add_flag("--timing", options->timing,
                  "Also print, on stderr, where the query's time went (connect, Hello, the status reply)");
    cmd->add_option("--token-file", options->query.token_file, "Token for a server that requires one");
    auto* tls = cmd->add_flag("--tls", options->query.tls, "Connect over TLS (a server started with --tls-cert)");
    cmd->add_option("--tls-ca", options->query.tls_ca_file,
                    "PEM CA (or the server's self-signed certificate) to verify the server against; implies --tls")
        ->excludes(tls);
    cmd->add_option("--timeout", options->query.timeout_seconds, "Seconds to wait for the answer")
        ->capture_default_str()
        ->check(CLI::PositiveNumber);
    cmd->callback([options] {
        if (!options->query.tls_ca_file.empty()) options->query.tls = true;
        ServerStatusTiming timing;
        if (options->timing) options->query.timing = &timing;
        Result<StatusReplyMsg> status = query_server_status(options->query);
        if (!status) fail("server-status: " + status.error());
        if (options->timing)
            std::fprintf(stderr, "timing: connect %.2f ms, hello %.2f ms, status %.2f ms\n", timing.connect_ms,
                         timing.hello_ms, timing.status_ms);
        if (options->json)
            std::cout << server_status_json(*status).dump(2) << "\n";
        else
            std::cout << server_status_text(*status);
    });
}

}  // namespace lc::client

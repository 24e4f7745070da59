#pragma once
// Each editor_client subcommand registers itself on the CLI11 app. A command
// that fails prints its error and throws CLI::RuntimeError(exit code).
#include <CLI/CLI.hpp>

namespace lc::client {

void add_bake_command(CLI::App& app);
void add_inspect_command(CLI::App& app);
void add_light_edit_commands(CLI::App& app);  // add-lights, remove-lights
void add_render_command(CLI::App& app);
void add_view_command(CLI::App& app);
void add_server_status_command(CLI::App& app);

}  // namespace lc::client

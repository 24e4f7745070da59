#pragma once
// Each editor_client subcommand registers itself on the CLI11 app. A command
// that fails prints its error and throws CLI::RuntimeError(exit code).
#include <CLI/CLI.hpp>

namespace lc::client {

void register_bake_command(CLI::App& app);
void register_inspect_command(CLI::App& app);
void register_light_edit_commands(CLI::App& app);  // add-lights, remove-lights
void register_render_command(CLI::App& app);
void register_view_command(CLI::App& app);
void register_server_status_command(CLI::App& app);

}  // namespace lc::client

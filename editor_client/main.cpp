// editor_client: bakes scenes on a lightmass_server, inspects trees, edits
// lights and renders with Vulkan. Every subcommand lives in commands/.
#include <CLI/CLI.hpp>

#include "editor_client/commands/commands.h"
#include "lightcuts/version.h"

int main(int argc, char** argv) {
    CLI::App app{"editor_client: Lightcuts bake client and Vulkan renderer"};
    app.require_subcommand(1);
    app.set_version_flag("--version", std::string("editor_client ") + lc::kVersion);
    lc::client::register_bake_command(app);
    lc::client::register_inspect_command(app);
    lc::client::register_render_command(app);
    lc::client::register_view_command(app);
    lc::client::register_light_edit_commands(app);
    lc::client::register_server_status_command(app);
    CLI11_PARSE(app, argc, argv);
    return 0;
}

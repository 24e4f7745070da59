#pragma once
// lightmass_server's --mpi-* flags: how a bake asking for ranks is launched.
#include <CLI/CLI.hpp>

#include "lightmass_server/bake/mpi_launch_options.h"

namespace lc::bake {

void add_mpi_flags(CLI::App& app, MpiLaunchOptions& mpi);

}  // namespace lc::bake

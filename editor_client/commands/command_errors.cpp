#include "editor_client/commands/command_errors.h"

#include <CLI/CLI.hpp>

#include <iostream>

namespace lc::client {

void fail(const std::string& message) {
    std::cerr << "error: " << message << "\n";
    throw CLI::RuntimeError(1);
}

}  // namespace lc::client

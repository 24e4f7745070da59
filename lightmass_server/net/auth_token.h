#pragma once
// Shared-secret authentication for servers that listen off loopback (the
// token file is read by protocol/token_file.h, the same rule as the client).
#include <filesystem>
#include <string>
#include <string_view>

#include "lightcuts/result.h"

namespace lc::bake {

// Compares in time that depends only on the lengths, not on where they differ.
bool tokens_equal(std::string_view expected, std::string_view given);

}  // namespace lc::bake

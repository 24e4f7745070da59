#pragma once
// Shared-secret authentication for servers that listen off loopback.
#include <filesystem>
#include <string>
#include <string_view>

#include "lightcuts/result.h"

namespace lc::bake {

// Reads a token file: the first line, surrounding white space removed. Refuses
// an empty token and one shorter than 16 characters.
Result<std::string> read_token_file(const std::filesystem::path& path);

// Compares in time that depends only on the lengths, not on where they differ.
bool tokens_equal(std::string_view expected, std::string_view given);

}  // namespace lc::bake

#pragma once
// A glTF copied to another folder must still reach its external files:
// relative buffer and image URIs (percent-encoded) and the environment's
// image path (gltf_environment.h) are rewritten for the new folder. data:
// URIs, absolute paths and URLs are left alone; so is everything when the
// folder does not change.
#include <nlohmann/json.hpp>

#include <filesystem>

namespace lc::client {

// `doc` was read from `source` and is about to be written to `out`.
void rewrite_uris(nlohmann::json& doc, const std::filesystem::path& source, const std::filesystem::path& out);

}  // namespace lc::client

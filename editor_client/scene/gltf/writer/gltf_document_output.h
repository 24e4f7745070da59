#pragma once
// Writing a glTF document the writers built (nlohmann JSON) to a file: .glb
// (the binary chunk in the container) or, for any other extension, .gltf
// JSON with the binary data embedded as a base64 data: URI. The file is
// written to a temporary name and renamed, so a failed write never leaves
// half a file. Arrays too large to hold as JSON objects (a million lights)
// are written element by element in place of a marker.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "lightcuts/result.h"

namespace lc::client {

// The elements of one array written in place of a marker string in the
// document, one element's JSON at a time: a million lights are never a
// million nlohmann objects at once (4 GB at 2^20 lights).
struct StreamedArray {
    nlohmann::json::json_pointer array;
    std::string marker;  // the array's last element in the document until it is written
    size_t count = 0;
    std::function<nlohmann::json(size_t)> element;
};

// Whether `out` names a .glb file (any case).
bool is_glb_path(const std::filesystem::path& out);

// Writes `doc` to `out` as .glb (with `bin` as its binary chunk) or as .gltf
// (with `bin` embedded as base64 in buffer `bin_buffer`, -1: none), with
// `arrays` written in place of their markers.
Status write_gltf_document(nlohmann::json doc, std::span<const uint8_t> bin, int bin_buffer,
                           const std::filesystem::path& out, const std::vector<StreamedArray>& arrays = {});

}  // namespace lc::client

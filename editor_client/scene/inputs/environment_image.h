#pragma once
// Loads an equirectangular environment from a Radiance .hdr file (stb_image),
// refusing with a message that names the problem: the file missing, empty,
// not HDR, truncated, 0x0 or beyond kMaxEquirectWidth x kMaxEquirectHeight
// (checked from the header, before any texel is decoded), or holding
// non-finite or negative texels.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>

#include "lightcuts/equirect_map.h"
#include "lightcuts/result.h"

namespace lc::client {

Result<EquirectMap> load_environment_image(const std::filesystem::path& path);
// `label` names the source in messages.
Result<EquirectMap> decode_environment_image(std::span<const uint8_t> bytes, const std::string& label);

}  // namespace lc::client

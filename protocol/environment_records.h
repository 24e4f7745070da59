#pragma once
// The environment channel, SCENEFORMATVERSION.SCENEGUID.env: one
// EnvironmentHeaderRecord (kind, width, height, intensity, rotation, sky
// parameters), then for a map `height` rows of `width` RGB float texels.
// Sent only when a scene has an environment or a sky. The reader is a push
// parser that validates the header and every texel as they arrive.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/environment.h"
#include "lightcuts/result.h"

namespace lc {


size_t environment_header_bytes();
size_t environment_texel_bytes();
// The largest channel a server accepts: the header and the largest map.
uint64_t max_environment_channel_bytes();

// Intensity finite and >= 0, rotation finite; a map within the limits with
// finite, non-negative texels, or valid sky parameters; not both, not neither.
Status validate_environment(const Environment& environment);

std::vector<uint8_t> encode_environment_channel(const Environment& environment);

class EnvironmentChannelReader {
public:
    // Fails on a bad header (unknown kind, size beyond the limits, non-finite
    // or negative values) or texel, naming it; nothing more is read after.
    Status consume(std::span<const uint8_t> bytes);
    // Succeeds only when the header and every texel it announces arrived, and nothing more.
    Result<Environment> finish();

private:
    Status take_header();
    Status take_texels(std::span<const uint8_t> bytes);

    std::vector<uint8_t> pending_;
    bool have_header_ = false;
    bool failed_ = false;
    uint64_t texels_expected_ = 0;
    Environment environment_;
};

Result<Environment> decode_environment_channel(std::span<const uint8_t> bytes);

}  // namespace lc

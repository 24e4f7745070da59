// The environment channel: a fixed-layout FlatBuffers header struct, then raw
// little-endian float texels (the structs are their own wire layout, and so
// are three floats).
#include "protocol/environment_records.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "lightcuts/status_macros.h"
#include "lightcuts_generated.h"

namespace lc {
namespace {

static_assert(sizeof(fb::EnvironmentHeaderRecord) == 32);
constexpr size_t kTexelBytes = 3 * sizeof(float);
constexpr uint64_t kMaxUpFrontTexels = 1u << 16;

enum class EnvironmentKind : uint8_t { kMap = 0, kSky = 1 };

Status validate_scale(float intensity, float rotation_deg) {
    if (!std::isfinite(intensity) || intensity < 0.0f)
        return make_error("environment intensity " + std::to_string(intensity) + " must be finite and >= 0");
    if (!std::isfinite(rotation_deg))
        return make_error("environment rotation " + std::to_string(rotation_deg) + " is not finite");
    return Ok{};
}

}  // namespace

size_t environment_header_bytes() { return sizeof(fb::EnvironmentHeaderRecord); }
size_t environment_texel_bytes() { return kTexelBytes; }
uint64_t max_environment_channel_bytes() {
    return environment_header_bytes() + uint64_t{kMaxEquirectWidth} * kMaxEquirectHeight * kTexelBytes;
}

Status validate_environment(const Environment& environment) {
    LC_RETURN_IF_ERROR(validate_scale(environment.intensity, environment.rotation_deg));
    if (environment.has_map() == environment.has_sky())
        return make_error(environment.has_map() ? "an environment is a map or a sun and sky, not both"
                                                : "an environment needs a map or a sun and sky");
    if (environment.has_sky()) return validate_sky_parameters(*environment.sky);
    const EquirectMap& map = environment.map;
    LC_RETURN_IF_ERROR(validate_equirect_size(map.width, map.height));
    if (map.texels.size() != size_t(map.width) * map.height)
        return make_error("environment map holds " + std::to_string(map.texels.size()) + " texels, not " +
                          std::to_string(map.width) + " x " + std::to_string(map.height));
    for (uint32_t y = 0; y < map.height; ++y)
        for (uint32_t x = 0; x < map.width; ++x) LC_RETURN_IF_ERROR(validate_equirect_texel(map.at(x, y), x, y));
    return Ok{};
}

std::vector<uint8_t> encode_environment_channel(const Environment& environment) {
    const SkyParameters sky = environment.sky.value_or(SkyParameters{0.0f, 0.0f, 0.0f});
    const fb::EnvironmentHeaderRecord header(
        static_cast<uint8_t>(environment.has_sky() ? EnvironmentKind::kSky : EnvironmentKind::kMap), 0, 0,
        environment.map.width, environment.map.height, environment.intensity, environment.rotation_deg,
        sky.elevation_deg, sky.azimuth_deg, sky.turbidity);
    std::vector<uint8_t> out(sizeof(header) + environment.map.texels.size() * kTexelBytes);
    std::memcpy(out.data(), &header, sizeof(header));
    uint8_t* texel = out.data() + sizeof(header);
    for (const glm::vec3& radiance : environment.map.texels) {
        const float rgb[3] = {radiance.x, radiance.y, radiance.z};
        std::memcpy(texel, rgb, kTexelBytes);
        texel += kTexelBytes;
    }
    return out;
}

Status EnvironmentChannelReader::take_header() {
    fb::EnvironmentHeaderRecord header;
    std::memcpy(static_cast<void*>(&header), pending_.data(), sizeof(header));
    pending_.erase(pending_.begin(), pending_.begin() + sizeof(header));
    have_header_ = true;
    environment_.intensity = header.intensity();
    environment_.rotation_deg = header.rotation_deg();
    LC_RETURN_IF_ERROR(validate_scale(environment_.intensity, environment_.rotation_deg));
    if (header.kind() == static_cast<uint8_t>(EnvironmentKind::kSky)) {
        if (header.width() != 0 || header.height() != 0)
            return make_error("a sun and sky carries no map, yet the header announces " +
                              std::to_string(header.width()) + " x " + std::to_string(header.height()) + " texels");
        environment_.sky = SkyParameters{header.sun_elevation_deg(), header.sun_azimuth_deg(), header.turbidity()};
        return validate_sky_parameters(*environment_.sky);
    }
    if (header.kind() != static_cast<uint8_t>(EnvironmentKind::kMap))
        return make_error("unknown environment kind " + std::to_string(header.kind()) + " (0: map, 1: sky)");
    LC_RETURN_IF_ERROR(validate_equirect_size(header.width(), header.height()));
    environment_.map.width = header.width();
    environment_.map.height = header.height();
    texels_expected_ = uint64_t{header.width()} * header.height();
    // A lying header must not make us reserve memory for texels that never come.
    environment_.map.texels.reserve(std::min<uint64_t>(texels_expected_, kMaxUpFrontTexels));
    return Ok{};
}

Status EnvironmentChannelReader::take_texels(std::span<const uint8_t> bytes) {
    pending_.insert(pending_.end(), bytes.begin(), bytes.end());
    size_t offset = 0;
    EquirectMap& map = environment_.map;
    for (; offset + kTexelBytes <= pending_.size(); offset += kTexelBytes) {
        if (map.texels.size() == texels_expected_)
            return make_error("more texels than the " + std::to_string(map.width) + " x " +
                              std::to_string(map.height) + " the header announced");
        float rgb[3];
        std::memcpy(rgb, pending_.data() + offset, kTexelBytes);
        const glm::vec3 radiance(rgb[0], rgb[1], rgb[2]);
        const auto index = uint32_t(map.texels.size());
        LC_RETURN_IF_ERROR(validate_equirect_texel(radiance, index % map.width, index / map.width));
        map.texels.push_back(radiance);
    }
    pending_.erase(pending_.begin(), pending_.begin() + std::ptrdiff_t(offset));
    if (!pending_.empty() && map.texels.size() == texels_expected_)
        return make_error("bytes after the last texel");
    return Ok{};
}

Status EnvironmentChannelReader::consume(std::span<const uint8_t> bytes) {
    if (failed_) return make_error("environment channel already refused");
    Status status = Ok{};
    if (!have_header_) {
        const size_t take = std::min(bytes.size(), environment_header_bytes() - pending_.size());
        pending_.insert(pending_.end(), bytes.begin(), bytes.begin() + std::ptrdiff_t(take));
        bytes = bytes.subspan(take);
        if (pending_.size() == environment_header_bytes()) status = take_header();
    }
    if (status && have_header_ && !bytes.empty()) {
        status = environment_.has_sky() ? Status(make_error("bytes after a sun and sky's header"))
                                        : take_texels(bytes);
    }
    if (!status) failed_ = true;
    return status;
}

Result<Environment> EnvironmentChannelReader::finish() {
    if (failed_) return make_error("environment channel already refused");
    if (!have_header_) return make_error("environment channel ended inside its header");
    if (!environment_.has_sky() && environment_.map.texels.size() != texels_expected_)
        return make_error("environment channel ended after " + std::to_string(environment_.map.texels.size()) +
                          " of " + std::to_string(texels_expected_) + " texels");
    if (!pending_.empty()) return make_error("environment channel ended inside a texel");
    return std::move(environment_);
}

Result<Environment> decode_environment_channel(std::span<const uint8_t> bytes) {
    EnvironmentChannelReader reader;
    LC_RETURN_IF_ERROR(reader.consume(bytes));
    return reader.finish();
}

}  // namespace lc

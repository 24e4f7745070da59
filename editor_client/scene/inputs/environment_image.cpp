#include "editor_client/scene/inputs/environment_image.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <string_view>
#include <vector>

#include "lightcuts/status_macros.h"

#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_HDR
#define STBI_NO_STDIO
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#endif
#include <stb_image.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace lc::client {
namespace {

struct HdrLayout {
    uint32_t width = 0;
    uint32_t height = 0;
    size_t pixels_offset = 0;  // first byte after the resolution line
};

// The header's end and the resolution line "-Y H +X W" (the only orientation stb reads).
Result<HdrLayout> read_layout(std::string_view text, const std::string& label) {
    const size_t blank = text.find("\n\n");
    if (blank == std::string_view::npos) return make_error(label + ": truncated inside the header");
    const size_t line_end = text.find('\n', blank + 2);
    if (line_end == std::string_view::npos) return make_error(label + ": truncated inside the resolution line");
    const std::string line(text.substr(blank + 2, line_end - blank - 2));
    long long height = -1, width = -1;
    char y_axis[3] = {}, x_axis[3] = {};
    if (std::sscanf(line.c_str(), "%2s %lld %2s %lld", y_axis, &height, x_axis, &width) != 4 ||
        std::string_view(y_axis) != "-Y" || std::string_view(x_axis) != "+X" || height < 0 || width < 0)
        return make_error(label + ": resolution line '" + line + "' is not '-Y HEIGHT +X WIDTH'");
    if (Status size = validate_equirect_size(uint64_t(width), uint64_t(height)); !size)
        return make_error(label + ": " + size.error());
    return HdrLayout{uint32_t(width), uint32_t(height), line_end + 1};
}

// stb fills what is missing with black; walk the scanlines (flat or
// run-length encoded, as stb reads them) to be sure every one is there.
Status check_complete(std::span<const uint8_t> bytes, const HdrLayout& layout, const std::string& label) {
    size_t at = layout.pixels_offset;
    const size_t size = bytes.size();
    auto truncated = [&](uint32_t row) {
        return make_error(label + ": truncated in scanline " + std::to_string(row) + " of " +
                          std::to_string(layout.height));
    };
    const bool run_length = layout.width >= 8 && layout.width < 32768 && at + 4 <= size && bytes[at] == 2 &&
                            bytes[at + 1] == 2 && !(bytes[at + 2] & 0x80);
    if (!run_length) {
        const uint64_t needed = uint64_t(layout.width) * layout.height * 4;
        if (size - at < needed) return truncated(uint32_t((size - at) / (uint64_t(layout.width) * 4)));
        return Ok{};
    }
    for (uint32_t row = 0; row < layout.height; ++row) {
        if (at + 4 > size) return truncated(row);
        at += 4;
        for (int channel = 0; channel < 4; ++channel) {
            for (uint32_t filled = 0; filled < layout.width;) {
                if (at >= size) return truncated(row);
                const uint8_t count = bytes[at++];
                const uint32_t run = count > 128 ? count - 128u : count;
                if (run == 0) return make_error(label + ": empty run in scanline " + std::to_string(row));
                at += count > 128 ? 1 : run;
                if (at > size) return truncated(row);
                filled += run;
            }
        }
    }
    return Ok{};
}

}  // namespace

Result<EquirectMap> decode_environment_image(std::span<const uint8_t> bytes, const std::string& label) {
    if (bytes.empty()) return make_error(label + ": the file is empty");
    const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    if (!text.starts_with("#?RADIANCE") && !text.starts_with("#?RGBE"))
        return make_error(label + ": not a Radiance HDR file (it does not start with '#?RADIANCE' or '#?RGBE')");
    Result<HdrLayout> layout = read_layout(text, label);
    if (!layout) return layout.failure();
    LC_RETURN_IF_ERROR(check_complete(bytes, *layout, label));
    int width = 0, height = 0, channels = 0;
    std::unique_ptr<float, decltype(&stbi_image_free)> pixels(
        stbi_loadf_from_memory(bytes.data(), int(bytes.size()), &width, &height, &channels, 3), &stbi_image_free);
    if (!pixels) return make_error(label + ": cannot decode: " + stbi_failure_reason());
    if (uint32_t(width) != layout->width || uint32_t(height) != layout->height)
        return make_error(label + ": decoded " + std::to_string(width) + " x " + std::to_string(height) +
                          " texels, the header says " + std::to_string(layout->width) + " x " +
                          std::to_string(layout->height));
    EquirectMap map{layout->width, layout->height, std::vector<glm::vec3>(size_t(width) * size_t(height))};
    const float* texel = pixels.get();
    for (uint32_t y = 0; y < map.height; ++y) {
        for (uint32_t x = 0; x < map.width; ++x, texel += 3) {
            const glm::vec3 radiance(texel[0], texel[1], texel[2]);
            if (Status valid = validate_equirect_texel(radiance, x, y); !valid)
                return make_error(label + ": " + valid.error());
            map.texels[size_t(y) * map.width + x] = radiance;
        }
    }
    return map;
}

Result<EquirectMap> load_environment_image(const std::filesystem::path& path) {
    const std::string label = "environment '" + path.string() + "'";
    std::error_code ec;
    const std::filesystem::file_status status = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(status)) return make_error(label + ": no such file");
    // A directory, FIFO or device is refused before it is opened (a FIFO would block, /dev/zero never ends).
    if (!std::filesystem::is_regular_file(status)) return make_error(label + ": not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) return make_error(label + ": cannot be opened");
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return decode_environment_image(bytes, label);
}

}  // namespace lc::client

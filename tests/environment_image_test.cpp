// Loading an equirectangular .hdr: a good file, and every bad one refused
// with a message naming the problem.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <sys/stat.h>

#include "editor_client/scene/inputs/environment_image.h"
#include "test_paths.h"

namespace lc::client {
namespace {

std::vector<uint8_t> hdr_header(uint32_t width, uint32_t height) {
    const std::string text = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " +
                             std::to_string(width) + "\n";
    return {text.begin(), text.end()};
}

// Flat RGBE texels: (128, 128, 128, 129) is 1.0, (64, 128, 192, 130) is (1, 2, 3).
std::vector<uint8_t> flat_hdr(uint32_t width, uint32_t height) {
    std::vector<uint8_t> bytes = hdr_header(width, height);
    for (uint32_t i = 0; i < width * height; ++i) {
        const bool coloured = i == 1;
        const uint8_t texel[4] = {uint8_t(coloured ? 64 : 128), 128, uint8_t(coloured ? 192 : 128),
                                  uint8_t(coloured ? 130 : 129)};
        bytes.insert(bytes.end(), texel, texel + 4);
    }
    return bytes;
}

// Run-length encoded scanlines (width >= 8): per channel one run of `width`.
std::vector<uint8_t> rle_hdr(uint32_t width, uint32_t height) {
    std::vector<uint8_t> bytes = hdr_header(width, height);
    for (uint32_t y = 0; y < height; ++y) {
        const uint8_t start[4] = {2, 2, uint8_t(width >> 8), uint8_t(width & 0xFF)};
        bytes.insert(bytes.end(), start, start + 4);
        for (uint8_t value : {128, 128, 128, 129}) {
            for (uint32_t filled = 0; filled < width; filled += 127) {
                bytes.push_back(uint8_t(128 + std::min(127u, width - filled)));
                bytes.push_back(value);
            }
        }
    }
    return bytes;
}

std::string refusal(const std::vector<uint8_t>& bytes) {
    auto map = decode_environment_image(bytes, "environment 'test.hdr'");
    return map ? std::string("accepted") : map.error();
}

TEST(EnvironmentImage, DecodesFlatAndRunLengthFiles) {
    auto flat = decode_environment_image(flat_hdr(4, 2), "flat");
    ASSERT_TRUE(flat) << flat.error();
    EXPECT_EQ(flat->width, 4u);
    EXPECT_EQ(flat->height, 2u);
    EXPECT_EQ(flat->at(0, 0), glm::vec3(1.0f));
    EXPECT_EQ(flat->at(1, 0), glm::vec3(1.0f, 2.0f, 3.0f));
    auto rle = decode_environment_image(rle_hdr(300, 3), "rle");
    ASSERT_TRUE(rle) << rle.error();
    EXPECT_EQ(rle->width, 300u);
    EXPECT_EQ(rle->at(299, 2), glm::vec3(1.0f));
}

TEST(EnvironmentImage, RefusesAMissingFile) {
    auto map = load_environment_image("/nonexistent/sky.hdr");
    ASSERT_FALSE(map);
    EXPECT_NE(map.error().find("'/nonexistent/sky.hdr': no such file"), std::string::npos) << map.error();
}

// Issue 27: a directory, a FIFO or a device said "no such file".
TEST(EnvironmentImage, RefusesWhatIsNotARegularFileByName) {
    const std::filesystem::path dir = test::make_temp_dir("environment-not-regular");
    const std::filesystem::path fifo = dir / "sky.hdr";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    for (const std::filesystem::path& path : {dir, fifo, std::filesystem::path("/dev/zero")}) {
        auto map = load_environment_image(path);
        ASSERT_FALSE(map);
        EXPECT_NE(map.error().find("'" + path.string() + "': not a regular file"), std::string::npos)
            << map.error();
    }
    std::filesystem::remove_all(dir);
}

TEST(EnvironmentImage, RefusesEmptyAndNonHdrFiles) {
    EXPECT_NE(refusal({}).find("empty"), std::string::npos);
    const std::string png = "\x89PNG\r\n\x1a\n....";
    EXPECT_NE(refusal({png.begin(), png.end()}).find("not a Radiance HDR file"), std::string::npos);
}

TEST(EnvironmentImage, RefusesTruncatedFiles) {
    for (const auto& whole : {flat_hdr(4, 2), rle_hdr(300, 3)}) {
        const std::vector<uint8_t> cut(whole.begin(), whole.end() - 3);
        EXPECT_NE(refusal(cut).find("truncated in scanline"), std::string::npos) << refusal(cut);
    }
    const auto header = hdr_header(4, 2);
    EXPECT_NE(refusal({header.begin(), header.begin() + 20}).find("truncated inside the header"), std::string::npos);
}

TEST(EnvironmentImage, RefusesEmptyAndAbsurdSizesBeforeDecoding) {
    EXPECT_NE(refusal(hdr_header(0, 0)).find("0 x 0: it has no texels"), std::string::npos) << refusal(hdr_header(0, 0));
    // The header alone announces it: nothing of the 100,000 x 50,000 texels is read.
    const std::string huge = refusal(hdr_header(100000, 50000));
    EXPECT_NE(huge.find("the limit is 8192 x 4096"), std::string::npos) << huge;
}

TEST(EnvironmentImage, LoadsFromAFile) {
    const auto path = std::filesystem::temp_directory_path() / "lc_environment_image_test.hdr";
    const auto bytes = flat_hdr(8, 4);
    std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    auto map = load_environment_image(path);
    std::filesystem::remove(path);
    ASSERT_TRUE(map) << map.error();
    EXPECT_EQ(map->texels.size(), 32u);
}

}  // namespace
}  // namespace lc::client

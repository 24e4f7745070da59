// OpenEXR images: float channels keep every bit (odd values included), half
// channels round to the nearest half, the header carries its attributes, and
// bad input is refused with a message naming the problem.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <string>

#include "editor_client/render/output/exr_image.h"
#include "test_paths.h"

namespace lc::client {
namespace {

// A 5x3 image of values a tone map would never see: tiny, huge, negative, signed zero, denormal.
FloatImage odd_values() {
    FloatImage image;
    image.width = 5;
    image.height = 3;
    for (uint32_t i = 0; i < image.width * image.height * 3; ++i)
        image.rgb.push_back(std::ldexp(1.0f + 0.001953125f * float(i), int(i % 11) - 5) * (i % 4 == 3 ? -1.0f : 1.0f));
    image.rgb[4] = -0.0f;
    image.rgb[7] = std::numeric_limits<float>::denorm_min();
    image.rgb[9] = 3.0e38f;
    return image;
}

class ExrImage : public ::testing::Test {
protected:
    void SetUp() override { dir_ = test::make_temp_dir("exr-image"); }
    void TearDown() override { std::filesystem::remove_all(dir_); }
    std::filesystem::path dir_;
};

TEST_F(ExrImage, FloatChannelsReadBackBitForBit) {
    const FloatImage image = odd_values();
    const auto path = dir_ / "odd.exr";
    ASSERT_TRUE(write_exr(path, image).ok());
    Result<FloatImage> back = read_exr(path);
    ASSERT_TRUE(back.ok()) << back.error();
    ASSERT_EQ(back->width, 5u);
    ASSERT_EQ(back->height, 3u);
    ASSERT_EQ(back->rgb.size(), image.rgb.size());
    for (size_t i = 0; i < image.rgb.size(); ++i)
        EXPECT_EQ(std::bit_cast<uint32_t>(back->rgb[i]), std::bit_cast<uint32_t>(image.rgb[i])) << "value " << i;
    EXPECT_FALSE(std::filesystem::exists(dir_ / "odd.exr.tmp"));
}

TEST_F(ExrImage, HalfChannelsRoundToTheNearestHalf) {
    FloatImage image;
    image.width = 2;
    image.height = 1;
    // 1 + 2^-11 lies halfway between two halves and rounds to even (1.0); 1 + 3 * 2^-11 rounds up.
    image.rgb = {1.0f + std::ldexp(1.0f, -11), 1.0f + 3.0f * std::ldexp(1.0f, -11), 0.25f, 65504.0f, -2.5f, 1e-3f};
    const auto path = dir_ / "half.exr";
    ExrWriteOptions options;
    options.pixels = ExrPixels::kHalf;
    Status written = write_exr(path, image, options);
    ASSERT_TRUE(written.ok()) << written.error();
    Result<FloatImage> back = read_exr(path);
    ASSERT_TRUE(back.ok()) << back.error();
    EXPECT_EQ(back->rgb[0], 1.0f);
    EXPECT_EQ(back->rgb[1], 1.0f + std::ldexp(1.0f, -9));
    EXPECT_EQ(back->rgb[2], 0.25f);
    EXPECT_EQ(back->rgb[3], 65504.0f);
    EXPECT_EQ(back->rgb[4], -2.5f);
    EXPECT_NEAR(back->rgb[5], 1e-3f, 1e-3f * std::ldexp(1.0f, -11));
    EXPECT_NE(back->rgb[5], 1e-3f);  // half, not float: the value moved
}

TEST_F(ExrImage, TheHeaderHoldsTheAttributes) {
    ExrWriteOptions options;
    options.attributes = {{"lightcuts.mode", "lightcuts"}, {"software", "editor_client test"}};
    const auto path = dir_ / "attributes.exr";
    ASSERT_TRUE(write_exr(path, odd_values(), options).ok());
    Result<std::string> mode = read_exr_attribute(path, "lightcuts.mode");
    ASSERT_TRUE(mode.ok()) << mode.error();
    EXPECT_EQ(*mode, "lightcuts");
    Result<std::string> missing = read_exr_attribute(path, "lightcuts.nothing");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().find("no string attribute 'lightcuts.nothing'"), std::string::npos);
}

TEST_F(ExrImage, ExrheaderOpensIt) {
    if (std::system("command -v exrheader > /dev/null 2>&1") != 0)
        GTEST_SKIP() << "exrheader is not installed (apt-get install openexr)";
    const auto path = dir_ / "opened.exr";
    ASSERT_TRUE(write_exr(path, odd_values()).ok());
    const auto log = dir_ / "exrheader.txt";
    const std::string command = "exrheader " + path.string() + " > " + log.string() + " 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << test::read_text(log);
    const std::string text = test::read_text(log);
    EXPECT_NE(text.find("R, 32-bit floating-point"), std::string::npos) << text;
    EXPECT_NE(text.find("zip"), std::string::npos) << text;
}

TEST_F(ExrImage, BadInputIsNamed) {
    FloatImage wrong = odd_values();
    wrong.rgb.pop_back();
    Status refused = write_exr(dir_ / "wrong.exr", wrong);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().find("pixel data does not match 5x3"), std::string::npos) << refused.error();

    const auto not_exr = dir_ / "not.exr";
    {
        std::ofstream out(not_exr);
        out << "PF\n1 1\n-1.0\n";
    }
    Result<FloatImage> read = read_exr(not_exr);
    ASSERT_FALSE(read.ok());
    EXPECT_NE(read.error().find("cannot read EXR " + not_exr.string()), std::string::npos) << read.error();
    EXPECT_TRUE(is_exr_path("a/B.EXR"));
    EXPECT_FALSE(is_exr_path("a/b.pfm"));
}

}  // namespace
}  // namespace lc::client

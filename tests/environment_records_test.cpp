// The environment channel: round trips, and every bad header or texel refused
// as it streams in, naming the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>

#include "protocol/channel_name.h"
#include "protocol/environment_records.h"

namespace lc {
namespace {

Environment small_map() {
    Environment environment;
    environment.map = EquirectMap{4, 2, {}};
    for (int i = 0; i < 8; ++i) environment.map.texels.push_back(glm::vec3(float(i), 0.5f, 2.0f * float(i)));
    environment.intensity = 1.5f;
    environment.rotation_deg = 30.0f;
    return environment;
}

// The channel's bytes with one header float (by byte offset) replaced.
std::vector<uint8_t> with_float_at(std::vector<uint8_t> bytes, size_t offset, float value) {
    std::memcpy(bytes.data() + offset, &value, sizeof(value));
    return bytes;
}

std::string refusal(const std::vector<uint8_t>& bytes) {
    auto decoded = decode_environment_channel(bytes);
    return decoded ? std::string("accepted") : decoded.error();
}

TEST(EnvironmentRecords, MapRoundTripsEvenByteByByte) {
    const Environment environment = small_map();
    const auto bytes = encode_environment_channel(environment);
    EXPECT_EQ(bytes.size(), environment_header_bytes() + 8 * environment_texel_bytes());
    EnvironmentChannelReader reader;
    for (uint8_t byte : bytes) ASSERT_TRUE(reader.consume({&byte, 1}));
    auto decoded = reader.finish();
    ASSERT_TRUE(decoded) << decoded.error();
    EXPECT_EQ(decoded->map.width, 4u);
    EXPECT_EQ(decoded->map.height, 2u);
    EXPECT_EQ(decoded->map.texels, environment.map.texels);
    EXPECT_EQ(decoded->intensity, 1.5f);
    EXPECT_EQ(decoded->rotation_deg, 30.0f);
    EXPECT_FALSE(decoded->has_sky());
}

TEST(EnvironmentRecords, SkyIsTheHeaderAlone) {
    Environment environment;
    environment.sky = SkyParameters{20.0f, 90.0f, 4.0f};
    const auto bytes = encode_environment_channel(environment);
    EXPECT_EQ(bytes.size(), environment_header_bytes());
    auto decoded = decode_environment_channel(bytes);
    ASSERT_TRUE(decoded) << decoded.error();
    ASSERT_TRUE(decoded->has_sky());
    EXPECT_EQ(*decoded->sky, *environment.sky);
    EXPECT_FALSE(decoded->has_map());
}

TEST(EnvironmentRecords, RefusesNonFiniteOrNegativeTexelsNamingThem) {
    const auto bytes = encode_environment_channel(small_map());
    const size_t texel5 = environment_header_bytes() + 5 * environment_texel_bytes();
    const std::string nan = refusal(with_float_at(bytes, texel5 + 4, std::numeric_limits<float>::quiet_NaN()));
    EXPECT_NE(nan.find("texel (1, 1) channel 1"), std::string::npos) << nan;
    const std::string inf = refusal(with_float_at(bytes, texel5, std::numeric_limits<float>::infinity()));
    EXPECT_NE(inf.find("finite"), std::string::npos) << inf;
    const std::string negative = refusal(with_float_at(bytes, texel5 + 8, -1.0f));
    EXPECT_NE(negative.find("non-negative"), std::string::npos) << negative;
}

TEST(EnvironmentRecords, RefusesBadHeaders) {
    const auto bytes = encode_environment_channel(small_map());
    // Offsets: kind 0, width 4, height 8, intensity 12, rotation 16, sky 20..31.
    auto with_u32 = [&](size_t offset, uint32_t value) {
        auto copy = bytes;
        std::memcpy(copy.data() + offset, &value, sizeof(value));
        return copy;
    };
    EXPECT_NE(refusal(with_u32(4, 0)).find("no texels"), std::string::npos);
    EXPECT_NE(refusal(with_u32(4, 100000)).find("the limit is 8192 x 4096"), std::string::npos);
    EXPECT_NE(refusal(with_float_at(bytes, 12, -2.0f)).find("intensity"), std::string::npos);
    EXPECT_NE(refusal(with_float_at(bytes, 16, std::numeric_limits<float>::infinity())).find("rotation"),
              std::string::npos);
    auto unknown = bytes;
    unknown[0] = 7;
    EXPECT_NE(refusal(unknown).find("unknown environment kind 7"), std::string::npos);
    Environment sky;
    sky.sky = SkyParameters{45.0f, 0.0f, 3.0f};
    const auto sky_bytes = encode_environment_channel(sky);
    EXPECT_NE(refusal(with_float_at(sky_bytes, 28, 40.0f)).find("turbidity"), std::string::npos);
    EXPECT_NE(refusal(with_float_at(sky_bytes, 20, -10.0f)).find("elevation"), std::string::npos);
}

TEST(EnvironmentRecords, RefusesTruncatedOrOverlongChannels) {
    const auto bytes = encode_environment_channel(small_map());
    EXPECT_NE(refusal({bytes.begin(), bytes.begin() + 10}).find("inside its header"), std::string::npos);
    EXPECT_NE(refusal({bytes.begin(), bytes.end() - 12}).find("7 of 8 texels"), std::string::npos);
    EXPECT_NE(refusal({bytes.begin(), bytes.end() - 2}).find("7 of 8 texels"), std::string::npos);
    auto longer = bytes;
    longer.insert(longer.end(), 12, 0);
    EXPECT_NE(refusal(longer).find("more texels"), std::string::npos);
}

TEST(EnvironmentRecords, NothingIsReadAfterARefusal) {
    const auto bytes = encode_environment_channel(small_map());
    EnvironmentChannelReader reader;
    auto bad = with_float_at(bytes, environment_header_bytes(), -1.0f);
    EXPECT_FALSE(reader.consume(bad));
    EXPECT_FALSE(reader.consume(bytes));
    EXPECT_FALSE(reader.finish());
}

TEST(EnvironmentRecords, ValidateEnvironmentWantsAMapOrASky) {
    Environment none;
    EXPECT_FALSE(validate_environment(none));
    Environment both = small_map();
    both.sky = SkyParameters{};
    EXPECT_FALSE(validate_environment(both));
    EXPECT_TRUE(validate_environment(small_map()));
}

TEST(EnvironmentRecords, ChannelIsNamedLikeTheScenes) {
    const Guid scene{1, 2, 3, 4};
    auto name = ChannelName::parse(environment_channel_name(scene));
    ASSERT_TRUE(name);
    EXPECT_EQ(name->extension, "env");
    EXPECT_EQ(name->data, scene);
    EXPECT_EQ(name->version, kSceneFormatVersionGuid);
}

}  // namespace
}  // namespace lc

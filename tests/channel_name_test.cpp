// Channel names: Unreal's CreateChannelName layout and the thesis's result channel.
#include "protocol/channel_name.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace lc {
namespace {

TEST(ChannelName, ThesisResultChannelIsExact) {
    // Version GUID first, then the data GUID ("LightcutsDataGUI"), then the extension.
    EXPECT_EQ(lightcuts_result_channel_name(),
              "4C69676874637574735665727369666E.4C696768746375747344617461475549.lcut");
}

TEST(ChannelName, CreateTakesDataThenVersionLikeUnreal) {
    const Guid data{1, 2, 3, 4};
    const Guid version{0xA, 0xB, 0xC, 0xD};
    EXPECT_EQ(create_channel_name(data, version, "ext"),
              "0000000A0000000B0000000C0000000D.00000001000000020000000300000004.ext");
}

TEST(ChannelName, SceneChannelUsesSceneFormatVersion) {
    const Guid scene{0xDEADBEEFu, 0x01234567u, 0x89ABCDEFu, 0x0u};
    const auto parsed = ChannelName::parse(scene_channel_name(scene));
    ASSERT_TRUE(parsed.has_value());
    EXPECT_EQ(parsed->version, kSceneFormatVersionGuid);
    EXPECT_EQ(parsed->data, scene);
    EXPECT_EQ(parsed->extension, "scene");
    EXPECT_EQ(scene_channel_name(scene),
              "4C435363656E65466F726D6174000001.DEADBEEF0123456789ABCDEF00000000.scene");
}

TEST(ChannelName, ParseInvertsToString) {
    const auto parsed = ChannelName::parse(lightcuts_result_channel_name());
    ASSERT_TRUE(parsed.has_value());
    EXPECT_EQ(parsed->version, kLightcutsVersionGuid);
    EXPECT_EQ(parsed->data, kLightcutsDataGuid);
    EXPECT_EQ(parsed->extension, "lcut");
    EXPECT_EQ(parsed->to_string(), lightcuts_result_channel_name());

    const ChannelName custom{Guid{9, 8, 7, 6}, Guid{1, 1, 1, 1}, "my_ext-2"};
    EXPECT_EQ(ChannelName::parse(custom.to_string())->to_string(), custom.to_string());
}

TEST(ChannelName, ParseAcceptsLowerCaseAndPrintsUpperCase) {
    const auto parsed = ChannelName::parse(
        "4c69676874637574735665727369666e.4c696768746375747344617461475549.lcut");
    ASSERT_TRUE(parsed.has_value());
    EXPECT_EQ(parsed->to_string(), lightcuts_result_channel_name());
}

TEST(ChannelName, ParseRejectsMalformedNames) {
    const std::string good = lightcuts_result_channel_name();
    for (const std::string& bad : std::vector<std::string>{
             std::string(), good.substr(0, good.size() - 5),  // no extension
             good + "/x",                                     // path separator
             good + ".more",                                  // a third dot
             good.substr(1),                                  // 31-digit version
             "X" + good.substr(1),                            // not hex
             good.substr(0, 32) + "-" + good.substr(33),      // wrong separator
             "4C696768-74637574-73566572-7369666E.4C696768746375747344617461475549.lcut",
             good.substr(0, 33) + "4C69676874637574734461746147554.lcut",  // 31-digit data
             good + std::string(70, 'a'),                                  // extension too long
             good.substr(0, good.size() - 4) + "lc t",                     // space in extension
         }) {
        EXPECT_FALSE(ChannelName::parse(bad).has_value()) << bad;
    }
}

}  // namespace
}  // namespace lc

// A channel on its way into the server: its kind by extension, its limits,
// and bytes past what it announced.
#include "lightmass_server/net/incoming_channel.h"

#include <gtest/gtest.h>

#include <vector>

namespace lc::bake {
namespace {

TEST(IncomingChannel, TheExtensionNamesTheKind) {
    EXPECT_EQ(channel_kind_of_extension("scene"), ChannelKind::kScene);
    EXPECT_EQ(channel_kind_of_extension("geom"), ChannelKind::kGeometry);
    EXPECT_EQ(channel_kind_of_extension("env"), ChannelKind::kEnvironment);
    EXPECT_FALSE(channel_kind_of_extension("lcut").has_value());
    EXPECT_FALSE(channel_kind_of_extension("").has_value());
}

TEST(IncomingChannel, EachKindHasItsOwnLimit) {
    for (ChannelKind kind : {ChannelKind::kScene, ChannelKind::kGeometry, ChannelKind::kEnvironment}) {
        EXPECT_GT(channel_limit(kind).max_bytes, 0u) << channel_kind_name(kind);
        EXPECT_FALSE(channel_limit(kind).words.empty()) << channel_kind_name(kind);
    }
    EXPECT_NE(channel_limit(ChannelKind::kScene).words.find(" lights"), std::string::npos);
    EXPECT_NE(channel_limit(ChannelKind::kEnvironment).words.find(" texels"), std::string::npos);
}

TEST(IncomingChannel, ReadsASceneAndKeepsItsBytesOnlyWhenRecording) {
    SceneLight light;
    light.intensity = 2.0f;
    const std::vector<SceneLight> lights{light, light};
    const std::vector<uint8_t> bytes = encode_scene_channel(lights);
    for (bool record : {false, true}) {
        IncomingChannel channel("x.scene", ChannelKind::kScene, bytes.size(), {});
        EXPECT_EQ(channel.kind(), ChannelKind::kScene);
        EXPECT_EQ(channel.label(), "scene channel 'x.scene'");
        ASSERT_TRUE(channel.consume(std::span(bytes).first(5), record).ok());
        EXPECT_FALSE(channel.complete());
        ASSERT_TRUE(channel.consume(std::span(bytes).subspan(5), record).ok());
        EXPECT_TRUE(channel.complete());
        EXPECT_EQ(channel.take_recorded().size(), record ? bytes.size() : 0u);
        auto read = std::get<SceneChannelReader>(channel.reader()).finish();
        ASSERT_TRUE(read.ok()) << read.error();
        EXPECT_EQ(read->size(), 2u);
    }
}

TEST(IncomingChannel, RefusesBytesPastTheAnnouncedTotal) {
    IncomingChannel channel("x.geom", ChannelKind::kGeometry, 4, {});
    EXPECT_EQ(channel.label(), "geometry channel 'x.geom'");
    const std::vector<uint8_t> five(5, 0);
    Status past = channel.consume(five, false);
    ASSERT_FALSE(past.ok());
    EXPECT_EQ(past.error(), "more bytes than the 4 announced");
    EXPECT_EQ(channel.received(), 0u);
}

}  // namespace
}  // namespace lc::bake

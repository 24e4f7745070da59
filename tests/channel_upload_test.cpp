// The client's channels go out one message at a time: open, chunks, close,
// and the result channel comes in checked.
#include "editor_client/bake/channel_upload.h"
#include "editor_client/bake/result_download.h"

#include <gtest/gtest.h>

#include "protocol/channel_name.h"

namespace lc::client {
namespace {

TEST(ChannelUpload, OpensWritesInChunksAndClosesEachChannelInOrder) {
    ChannelUpload upload({{1, "a.scene", {1, 2, 3, 4, 5, 6, 7}}, {2, "b.env", {}}}, 3);
    std::vector<std::string> seen;
    while (std::optional<Message> m = upload.next_message()) {
        if (auto* open = std::get_if<OpenChannelMsg>(&*m)) seen.push_back("open " + open->name);
        if (auto* write = std::get_if<WriteChannelMsg>(&*m))
            seen.push_back("write " + std::to_string(write->offset) + "+" + std::to_string(write->bytes().size()));
        if (auto* close = std::get_if<CloseChannelMsg>(&*m)) seen.push_back("close " + std::to_string(close->channel_id));
    }
    EXPECT_TRUE(upload.done());
    const std::vector<std::string> expected{"open a.scene", "write 0+3", "write 3+3", "write 6+1",
                                            "close 1",      "open b.env", "close 2"};
    EXPECT_EQ(seen, expected);
    EXPECT_EQ(upload.take_channels()[0].bytes.size(), 7u);
}

TEST(ResultDownload, RefusesAnUnexpectedNameASecondOpenAndWritesOutOfOrder) {
    ResultDownload download(TreeImport::kNodes, true);
    EXPECT_FALSE(download.open(OpenChannelMsg{7, "not a channel", 4}).ok());
    const std::string name = lightcuts_result_channel_name();
    ASSERT_TRUE(download.open(OpenChannelMsg{7, name, 4}).ok());
    EXPECT_EQ(download.open(OpenChannelMsg{8, name, 4}).error(), "server opened a second result channel");
    EXPECT_EQ(download.write(WriteChannelMsg{8, 0, {1}}).error(), "server wrote to channel 8 which is not open");
    EXPECT_EQ(download.write(WriteChannelMsg{7, 2, {1}}).error(),
              "result channel out of order or longer than announced");
    EXPECT_FALSE(download.close(CloseChannelMsg{8}).ok());
    EXPECT_FALSE(download.closed());
    EXPECT_TRUE(download.close(CloseChannelMsg{7}).ok());
    EXPECT_TRUE(download.closed());
}

}  // namespace
}  // namespace lc::client

// A tree kept on disk as the result channel's bytes (result_channel_file.h),
// as a bake over MPI ranks leaves it: adopted only when every record and the
// structure check out, streamed to the client as the very frames an
// in-memory tree gives, and removed once its last owner lets it go.
#include "lightmass_server/bake/result_channel_file.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "lightmass_server/net/result_stream.h"
#include "lightmass_server/builders/tree_builder.h"
#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/codec.h"
#include "protocol/frame_decoder.h"
#include "tree_fixtures.h"

namespace lc::bake {
namespace {
namespace fs = std::filesystem;

LightTree built_tree(int lights) {
    std::mt19937_64 rng(5);
    const std::vector<SceneLight> scene =
        test::random_lights_in_box(rng, lights, LightType::kPoint, glm::vec3(0.0f), glm::vec3(10.0f), false);
    BuildOptions options;
    options.builder = BuilderKind::kLbvh;
    Result<BuildResult> built = build_light_tree(scene, options, {});
    EXPECT_TRUE(built.ok()) << (built ? "" : built.error());
    return built ? std::move(built->tree) : LightTree{};
}

fs::path write_channel(const std::string& name, const std::vector<uint8_t>& bytes) {
    const fs::path path = fs::temp_directory_path() / (name + "-" + std::to_string(getpid()) + ".lcut");
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    return path;
}

BakeDoneMsg done_for(const LightTree& tree) {
    BakeDoneMsg done;
    done.bake_id = 9;
    done.result_channel = lightcuts_result_channel_name();
    done.node_count = uint32_t(tree.nodes.size());
    done.leaf_count = tree.leaf_count;
    done.effects = {"a census line"};
    return done;
}

// Every frame's bytes, in order.
template <typename Source>
std::vector<std::vector<uint8_t>> frames_of(Source source, const BakeDoneMsg& done, size_t chunk_bytes) {
    ResultStream stream(std::move(source), 3, done, chunk_bytes);
    std::vector<std::vector<uint8_t>> frames;
    while (auto frame = stream.next_frame())
        frames.emplace_back(frame->bytes().begin(), frame->bytes().end());
    return frames;
}

TEST(ResultChannelFile, StreamsTheSameFramesAsTheTreeInMemory) {
    const LightTree tree = built_tree(3000);
    const fs::path path = write_channel("stream-same", encode_result_channel(tree));
    Result<std::shared_ptr<const ResultChannelFile>> file = ResultChannelFile::adopt(path);
    ASSERT_TRUE(file.ok()) << file.error();
    EXPECT_EQ((*file)->node_count(), tree.nodes.size());
    EXPECT_EQ((*file)->leaf_count(), tree.leaf_count);
    const BakeDoneMsg done = done_for(tree);
    for (size_t chunk_bytes : {size_t(1000), size_t(64 * 1024), kDefaultChunkBytes}) {
        const auto from_tree = frames_of(std::make_shared<const LightTree>(tree), done, chunk_bytes);
        const auto from_file = frames_of(*file, done, chunk_bytes);
        ASSERT_GT(from_tree.size(), 3u);  // open, some chunks, close, done
        EXPECT_EQ(from_file, from_tree) << "chunks of " << chunk_bytes << " bytes";
    }
    EXPECT_TRUE(fs::exists(path));
    file = make_error("let go");
    EXPECT_FALSE(fs::exists(path)) << "the last owner let go and the file stayed";
}

TEST(ResultChannelFile, ABrokenFileIsRefusedNamingTheProblemAndRemoved) {
    const LightTree tree = built_tree(200);
    std::vector<uint8_t> bytes = encode_result_channel(tree);
    const fs::path short_path = write_channel("short", std::vector<uint8_t>(bytes.begin(), bytes.end() - 7));
    Result<std::shared_ptr<const ResultChannelFile>> cut = ResultChannelFile::adopt(short_path);
    ASSERT_FALSE(cut.ok());
    EXPECT_NE(cut.error().find("result"), std::string::npos) << cut.error();
    EXPECT_FALSE(fs::exists(short_path));

    // The root's left child pointing at the root itself: a record that fails its own check.
    LightTree looped = tree;
    looped.nodes[0].left = 0;
    const fs::path looped_path = write_channel("looped", encode_result_channel(looped));
    Result<std::shared_ptr<const ResultChannelFile>> refused = ResultChannelFile::adopt(looped_path);
    ASSERT_FALSE(refused.ok());
    EXPECT_NE(refused.error().find("node 0"), std::string::npos) << refused.error();
    EXPECT_FALSE(fs::exists(looped_path));

    const Result<std::shared_ptr<const ResultChannelFile>> missing =
        ResultChannelFile::adopt(fs::temp_directory_path() / "no-such-result-file.lcut");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().find("cannot open"), std::string::npos) << missing.error();
}

TEST(ResultChannelFile, AFileCutShortWhileStreamingEndsTheStreamWithAnError) {
    const LightTree tree = built_tree(3000);
    const fs::path path = write_channel("cut-while-streaming", encode_result_channel(tree));
    Result<std::shared_ptr<const ResultChannelFile>> file = ResultChannelFile::adopt(path);
    ASSERT_TRUE(file.ok()) << file.error();
    fs::resize_file(path, 5000);
    ResultStream stream(*file, 3, done_for(tree), 4096);
    std::optional<Message> last;
    size_t frames = 0;
    while (auto frame = stream.next_frame()) {
        Result<Message> message = decode_message(frame->bytes().subspan(kFrameHeaderBytes));
        ASSERT_TRUE(message.ok()) << message.error();
        last = std::move(message.value());
        ++frames;
    }
    ASSERT_TRUE(last.has_value());
    const auto* error = std::get_if<ErrorMsg>(&*last);
    ASSERT_NE(error, nullptr) << "the stream did not end with an Error";
    EXPECT_EQ(error->bake_id, 9u);
    EXPECT_EQ(error->code, ErrorCode::kBakeFailed);
    EXPECT_NE(error->text.find("the result could not be sent"), std::string::npos) << error->text;
    EXPECT_EQ(frames, 3u);  // open, the first chunk (bytes 0..4096), the error
}

}  // namespace
}  // namespace lc::bake

// Issue 14, item 6: glTF buffer and image URIs were followed anywhere on the
// filesystem, and a URI naming a FIFO hung the loader. Now: data: URIs and
// regular files inside the scene's folder, unless --allow-external-resources;
// never a FIFO.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <fstream>
#include <future>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "editor_client/scene/gltf/gltf_buffer_sizes.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "test_paths.h"

namespace lc::client {
namespace {

using json = nlohmann::json;
using ::testing::HasSubstr;

// One triangle: positions (36 bytes) then uint16 indices (6 bytes), padded to 44.
std::vector<uint8_t> triangle_buffer() {
    const float positions[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint16_t indices[3] = {0, 1, 2};
    std::vector<uint8_t> bytes(44, 0);
    std::memcpy(bytes.data(), positions, sizeof positions);
    std::memcpy(bytes.data() + 36, indices, sizeof indices);
    return bytes;
}

// A scene whose one buffer is `buffer_uri`; `image_uri`, when given, is a
// base-colour texture's image.
json triangle_scene(const std::string& buffer_uri, const std::string& image_uri = "") {
    json doc = {
        {"asset", {{"version", "2.0"}}},
        {"scene", 0},
        {"scenes", {{{"nodes", {0}}}}},
        {"nodes", {{{"mesh", 0}}}},
        {"meshes",
         {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}, {"material", 0}}}}}}},
        {"materials", {json::object()}},
        {"accessors",
         {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}},
          {{"bufferView", 1}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}},
        {"bufferViews",
         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}},
          {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 6}}}},
        {"buffers", {{{"byteLength", 44}, {"uri", buffer_uri}}}},
    };
    if (!image_uri.empty()) {
        doc["images"] = {{{"uri", image_uri}}};
        doc["textures"] = {{{"source", 0}}};
        doc["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"] = {{"index", 0}};
    }
    return doc;
}

void write_bytes(const std::filesystem::path& path, const std::vector<uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary);
    out.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

// triangle_buffer() as a data: URI.
constexpr const char* kTriangleDataUri =
    "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA=";

class GltfResourceAccess : public ::testing::Test {
protected:
    void SetUp() override {
        root_ = lc::test::make_temp_dir("gltf-resources");
        scene_dir_ = root_ / "scene";
        std::filesystem::create_directories(scene_dir_ / "buffers");
        write_bytes(scene_dir_ / "buffers" / "triangle.bin", triangle_buffer());
        write_bytes(root_ / "outside.bin", triangle_buffer());
    }
    void TearDown() override { std::filesystem::remove_all(root_); }

    std::filesystem::path write_scene(const json& doc, const std::string& name = "scene.gltf") {
        const std::filesystem::path path = scene_dir_ / name;
        std::ofstream(path) << doc.dump();
        return path;
    }
    Result<Scene> load(const json& doc, bool allow_external = false) {
        GltfLoadOptions options;
        options.allow_external_resources = allow_external;
        warnings_.clear();
        return load_scene(write_scene(doc), warnings_, options);
    }

    std::filesystem::path root_;
    std::filesystem::path scene_dir_;
    std::vector<std::string> warnings_;
};

TEST_F(GltfResourceAccess, RelativeUriInsideTheSceneFolderLoads) {
    Result<Scene> scene = load(triangle_scene("buffers/triangle.bin"));
    ASSERT_TRUE(scene.ok()) << scene.error();
    ASSERT_EQ(scene->meshes.size(), 1u);
    EXPECT_EQ(scene->meshes[0].indices.size(), 3u);
    // "./" and a detour that stays inside are still inside.
    EXPECT_TRUE(load(triangle_scene("./buffers/../buffers/triangle.bin")).ok());
}

// Issue 27: a buffer of byteLength 44 naming a 2 GB (sparse) file read all of
// it before tinygltf's "File size mismatch"; the size is compared first now.
TEST_F(GltfResourceAccess, BufferFileOfAnotherSizeThanItsByteLengthIsRefusedUnread) {
    const std::filesystem::path huge = scene_dir_ / "buffers" / "huge.bin";
    write_bytes(huge, {});
    ASSERT_EQ(::truncate(huge.c_str(), off_t(2) << 30), 0) << std::strerror(errno);
    Result<Scene> scene = load(triangle_scene("buffers/huge.bin"));
    ASSERT_FALSE(scene.ok());
    EXPECT_THAT(scene.error(),
                HasSubstr("holds 2147483648 bytes but its buffer's byteLength is 44; not read"));
}

TEST(GltfBufferSizes, ReadFromGltfTextAndGlbJsonChunkWithoutDataUris) {
    const std::string text =
        R"({"buffers":[{"uri":"a.bin","byteLength":7},{"uri":"data:,x","byteLength":1}]})";
    const auto* bytes = reinterpret_cast<const uint8_t*>(text.data());
    std::vector<BufferFileSize> sizes = external_buffer_sizes({bytes, text.size()});
    ASSERT_EQ(sizes.size(), 1u);
    EXPECT_EQ(sizes[0].uri, "a.bin");
    EXPECT_EQ(sizes[0].byte_length, 7u);
    // The same JSON as a .glb's first chunk.
    std::vector<uint8_t> glb = {'g', 'l', 'T', 'F', 2, 0, 0, 0, 0, 0, 0, 0};
    const uint32_t length = uint32_t(text.size());
    glb.insert(glb.end(), {uint8_t(length), uint8_t(length >> 8), 0, 0, 'J', 'S', 'O', 'N'});
    glb.insert(glb.end(), text.begin(), text.end());
    sizes = external_buffer_sizes(glb);
    ASSERT_EQ(sizes.size(), 1u);
    EXPECT_EQ(sizes[0].byte_length, 7u);
    EXPECT_TRUE(external_buffer_sizes(std::vector<uint8_t>{'{'}).empty());
}

TEST_F(GltfResourceAccess, ParentDirectoryUriIsRefusedUnlessAllowed) {
    Result<Scene> scene = load(triangle_scene("../outside.bin"));
    ASSERT_FALSE(scene.ok());
    EXPECT_THAT(scene.error(), HasSubstr("lies outside the scene's folder"));
    EXPECT_THAT(scene.error(), HasSubstr("--allow-external-resources"));
    Result<Scene> allowed = load(triangle_scene("../outside.bin"), /*allow_external=*/true);
    ASSERT_TRUE(allowed.ok()) << allowed.error();
    EXPECT_EQ(allowed->meshes.size(), 1u);
}

TEST_F(GltfResourceAccess, AbsolutePathIsRefusedUnlessAllowed) {
    const std::string absolute = (root_ / "outside.bin").string();
    Result<Scene> scene = load(triangle_scene(absolute));
    ASSERT_FALSE(scene.ok());
    EXPECT_THAT(scene.error(), HasSubstr("outside.bin"));
    EXPECT_THAT(scene.error(), HasSubstr("lies outside the scene's folder"));
    EXPECT_TRUE(load(triangle_scene(absolute), /*allow_external=*/true).ok());
}

TEST_F(GltfResourceAccess, SymlinkInsideThatPointsOutsideIsRefused) {
    std::filesystem::create_symlink(root_ / "outside.bin", scene_dir_ / "link.bin");
    Result<Scene> scene = load(triangle_scene("link.bin"));
    ASSERT_FALSE(scene.ok());
    EXPECT_THAT(scene.error(), HasSubstr("lies outside the scene's folder"));
}

TEST_F(GltfResourceAccess, FifoIsRefusedWithoutBlockingEvenWhenExternalIsAllowed) {
    const std::filesystem::path fifo = scene_dir_ / "pipe.bin";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0) << std::strerror(errno);
    for (bool allow_external : {false, true}) {
        const std::filesystem::path path = write_scene(triangle_scene("pipe.bin"));
        auto loading = std::async(std::launch::async, [path, allow_external] {
            GltfLoadOptions options;
            options.allow_external_resources = allow_external;
            std::vector<std::string> warnings;
            return load_scene(path, warnings, options);
        });
        if (loading.wait_for(std::chrono::seconds(20)) != std::future_status::ready) {
            // Release the blocked reader so the test can report instead of hanging.
            const int writer = ::open(fifo.c_str(), O_WRONLY | O_NONBLOCK);
            if (writer >= 0) ::close(writer);
            FAIL() << "the loader blocked on a FIFO";
        }
        Result<Scene> scene = loading.get();
        ASSERT_FALSE(scene.ok());
        EXPECT_THAT(scene.error(), HasSubstr("is not a regular file"));
    }
    // The scene file itself as a FIFO: refused before it is opened.
    std::vector<std::string> warnings;
    Result<Scene> scene = load_scene(fifo, warnings);
    ASSERT_FALSE(scene.ok());
    EXPECT_THAT(scene.error(), HasSubstr("not a regular file"));
}

TEST_F(GltfResourceAccess, ImageOutsideTheFolderIsDroppedWithAWarning) {
    write_bytes(root_ / "outside.png", {0x89, 'P', 'N', 'G'});
    Result<Scene> scene = load(triangle_scene("buffers/triangle.bin", "../outside.png"));
    ASSERT_TRUE(scene.ok()) << scene.error();
    EXPECT_TRUE(scene->textures.empty());
    bool warned = false;
    for (const std::string& w : warnings_) warned |= w.find("lies outside") != std::string::npos;
    EXPECT_TRUE(warned) << ::testing::PrintToString(warnings_);
}

TEST_F(GltfResourceAccess, FromMemoryReadsDataUrisAndNoFiles) {
    auto from_memory = [](const json& doc, const std::filesystem::path& folder) {
        const std::string text = doc.dump();
        std::vector<std::string> warnings;
        return load_scene_from_memory(
            std::span(reinterpret_cast<const uint8_t*>(text.data()), text.size()), folder,
            warnings);
    };
    Result<Scene> embedded =
        from_memory(triangle_scene(kTriangleDataUri), {});
    ASSERT_TRUE(embedded.ok()) << embedded.error();
    EXPECT_EQ(embedded->meshes.size(), 1u);

    Result<Scene> external = from_memory(triangle_scene("buffers/triangle.bin"), {});
    ASSERT_FALSE(external.ok());
    EXPECT_THAT(external.error(), HasSubstr("reads none"));
    // Given a folder, memory loads follow the same rule as files.
    EXPECT_TRUE(from_memory(triangle_scene("buffers/triangle.bin"), scene_dir_).ok());
    EXPECT_FALSE(from_memory(triangle_scene("../outside.bin"), scene_dir_).ok());
}

}  // namespace
}  // namespace lc::client

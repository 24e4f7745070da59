// A scene file mapped read-only (mapped_file.h): its bytes as on disk, still
// readable after their pages are released, and the same refusals as the
// loader's reads (a directory, a FIFO, a missing file).
#include "editor_client/scene/inputs/mapped_file.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <string>

#include "test_paths.h"

namespace lc::client {
namespace {

namespace fs = std::filesystem;

TEST(MappedFile, ReadsTheFileAndKeepsReleasedBytesReadable) {
    const fs::path dir = test::make_temp_dir("mapped-file");
    std::string text;
    for (int i = 0; i < 50000; ++i) text += std::to_string(i * 7) + ",";
    std::ofstream(dir / "f.json", std::ios::binary) << text;
    Result<MappedFile> file = MappedFile::open(dir / "f.json");
    ASSERT_TRUE(file.ok()) << file.error();
    const std::span<const uint8_t> bytes = file->bytes();
    ASSERT_EQ(bytes.size(), text.size());
    EXPECT_EQ(std::string(bytes.begin(), bytes.end()), text);
    file->release_before(text.size() / 2);
    file->release_before(text.size() / 4);  // behind what is released already: nothing to do
    file->release_before(text.size() + 100);
    EXPECT_EQ(std::string(bytes.begin(), bytes.end()), text);

    MappedFile moved = std::move(file.value());
    EXPECT_TRUE(file->bytes().empty());
    EXPECT_EQ(moved.bytes().size(), text.size());
    fs::remove_all(dir);
}

TEST(MappedFile, MapsAnEmptyFileAsNoBytes) {
    const fs::path dir = test::make_temp_dir("mapped-file-empty");
    std::ofstream(dir / "empty.gltf").close();
    Result<MappedFile> file = MappedFile::open(dir / "empty.gltf");
    ASSERT_TRUE(file.ok()) << file.error();
    EXPECT_TRUE(file->bytes().empty());
    fs::remove_all(dir);
}

TEST(MappedFile, RefusesWhatIsNotARegularFile) {
    const fs::path dir = test::make_temp_dir("mapped-file-refusals");
    Result<MappedFile> folder = MappedFile::open(dir);
    ASSERT_FALSE(folder.ok());
    EXPECT_NE(folder.error().find("is not a regular file"), std::string::npos) << folder.error();
    ASSERT_EQ(::mkfifo((dir / "fifo").c_str(), 0600), 0);
    Result<MappedFile> fifo = MappedFile::open(dir / "fifo");  // returns at once: opened non-blocking
    ASSERT_FALSE(fifo.ok());
    EXPECT_NE(fifo.error().find("is not a regular file"), std::string::npos) << fifo.error();
    Result<MappedFile> missing = MappedFile::open(dir / "missing.gltf");
    ASSERT_FALSE(missing.ok());
    EXPECT_NE(missing.error().find("cannot open"), std::string::npos) << missing.error();
    fs::remove_all(dir);
}

}  // namespace
}  // namespace lc::client

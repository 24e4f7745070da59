// Channel dumps: header layout, atomic writes, and loud refusal of stale,
// foreign, truncated or padded files.
#include "protocol/dump.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/codec.h"
#include "test_paths.h"

namespace lc {
namespace {

namespace fs = std::filesystem;

std::vector<uint8_t> read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return std::vector<uint8_t>((std::istreambuf_iterator<char>(in)),
                                std::istreambuf_iterator<char>());
}

void write_file(const fs::path& path, const std::vector<uint8_t>& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
}

uint64_t le_at(const std::vector<uint8_t>& bytes, size_t offset, int width) {
    uint64_t v = 0;
    for (int i = width - 1; i >= 0; --i) v = (v << 8) | bytes[offset + static_cast<size_t>(i)];
    return v;
}

void put_le(std::vector<uint8_t>& bytes, size_t offset, uint64_t v, int width) {
    for (int i = 0; i < width; ++i)
        bytes[offset + static_cast<size_t>(i)] = static_cast<uint8_t>(v >> (8 * i));
}

ChannelDump sample_dump() {
    ChannelDump dump;
    dump.channel_name = lightcuts_result_channel_name();
    for (int i = 0; i < 300; ++i) dump.payload.push_back(static_cast<uint8_t>(i * 13));
    return dump;
}

std::string read_error(const fs::path& path) {
    Result<ChannelDump> dump = read_dump(path);
    return dump.ok() ? std::string("(accepted)") : dump.error();
}

TEST(Dump, PathIsChannelNamePlusExtension) {
    EXPECT_EQ(dump_path_for("/tmp/rec", "A.B.lcut"), fs::path("/tmp/rec/A.B.lcut.dump"));
}

TEST(Dump, RoundTripsNameAndPayload) {
    const fs::path dir = test::make_temp_dir("dump-roundtrip");
    const ChannelDump dump = sample_dump();
    const fs::path path = dump_path_for(dir, dump.channel_name);
    ASSERT_TRUE(write_dump(path, dump).ok());
    Result<ChannelDump> read = read_dump(path);
    ASSERT_TRUE(read.ok()) << read.error();
    EXPECT_EQ(read->channel_name, dump.channel_name);
    EXPECT_EQ(read->payload, dump.payload);

    const ChannelDump empty{"", {}};
    ASSERT_TRUE(write_dump(dir / "empty.dump", empty).ok());
    Result<ChannelDump> read_empty = read_dump(dir / "empty.dump");
    ASSERT_TRUE(read_empty.ok()) << read_empty.error();
    EXPECT_TRUE(read_empty->channel_name.empty());
    EXPECT_TRUE(read_empty->payload.empty());
    fs::remove_all(dir);
}

// The streaming read hands the payload over in chunks of the size asked for,
// after the header, and stops at the first error a callback returns.
TEST(Dump, StreamsThePayloadInChunks) {
    const fs::path dir = test::make_temp_dir("dump-stream");
    const ChannelDump dump = sample_dump();
    ASSERT_TRUE(write_dump(dir / "x.dump", dump).ok());
    DumpHeader header;
    std::vector<uint8_t> payload;
    std::vector<size_t> chunks;
    Status read = read_dump_streaming(
        dir / "x.dump",
        [&](const DumpHeader& h) -> Status {
            EXPECT_TRUE(payload.empty());
            header = h;
            return Ok{};
        },
        [&](std::span<const uint8_t> chunk) -> Status {
            chunks.push_back(chunk.size());
            payload.insert(payload.end(), chunk.begin(), chunk.end());
            return Ok{};
        },
        128);
    ASSERT_TRUE(read.ok()) << read.error();
    EXPECT_EQ(header.channel_name, dump.channel_name);
    EXPECT_EQ(header.payload_bytes, dump.payload.size());
    EXPECT_EQ(payload, dump.payload);
    EXPECT_EQ(chunks, (std::vector<size_t>{128, 128, 44}));

    int calls = 0;
    Status stopped = read_dump_streaming(
        dir / "x.dump", [](const DumpHeader&) -> Status { return Ok{}; },
        [&](std::span<const uint8_t>) -> Status {
            ++calls;
            return make_error("enough");
        },
        128);
    EXPECT_FALSE(stopped.ok());
    EXPECT_EQ(stopped.error(), "enough");
    EXPECT_EQ(calls, 1);
    fs::remove_all(dir);
}

TEST(Dump, HeaderLayoutIsAsDocumented) {
    const fs::path dir = test::make_temp_dir("dump-layout");
    const ChannelDump dump = sample_dump();
    ASSERT_TRUE(write_dump(dir / "x.dump", dump).ok());
    const auto bytes = read_file(dir / "x.dump");
    const size_t name = dump.channel_name.size();
    ASSERT_EQ(bytes.size(), 8 + 4 + 8 + 4 + name + 8 + dump.payload.size());
    EXPECT_EQ(std::string(bytes.begin(), bytes.begin() + 8), "LCDUMP01");
    EXPECT_EQ(le_at(bytes, 8, 4), kDumpVersion);
    EXPECT_EQ(le_at(bytes, 12, 8), schema_hash());
    EXPECT_EQ(le_at(bytes, 20, 4), name);
    EXPECT_EQ(std::string(bytes.begin() + 24, bytes.begin() + 24 + static_cast<long>(name)),
              dump.channel_name);
    EXPECT_EQ(le_at(bytes, 24 + name, 8), dump.payload.size());
    EXPECT_TRUE(std::equal(dump.payload.begin(), dump.payload.end(),
                           bytes.begin() + 32 + static_cast<long>(name)));
    fs::remove_all(dir);
}

TEST(Dump, WritesAtomicallyAndReplacesOldDumps) {
    const fs::path dir = test::make_temp_dir("dump-atomic");
    ChannelDump dump = sample_dump();
    const fs::path path = dir / "channel.dump";
    ASSERT_TRUE(write_dump(path, dump).ok());
    dump.payload.assign(10, 7);
    ASSERT_TRUE(write_dump(path, dump).ok());
    EXPECT_EQ(read_dump(path)->payload, dump.payload);
    // Only the dump itself remains: no temporary files.
    size_t files = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        ++files;
        EXPECT_EQ(entry.path().filename(), "channel.dump");
    }
    EXPECT_EQ(files, 1u);
    // A directory that does not exist is an error, not a crash.
    Status status = write_dump(dir / "missing" / "x.dump", dump);
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().find("missing"), std::string::npos) << status.error();
    fs::remove_all(dir);
}

TEST(Dump, RefusesForeignOrStaleFiles) {
    const fs::path dir = test::make_temp_dir("dump-refuse");
    const fs::path path = dir / "x.dump";
    ASSERT_TRUE(write_dump(path, sample_dump()).ok());
    const auto good = read_file(path);

    auto bytes = good;
    bytes[0] = 'X';
    write_file(path, bytes);
    EXPECT_NE(read_error(path).find("LCDUMP01"), std::string::npos) << read_error(path);

    bytes = good;
    put_le(bytes, 8, 2, 4);
    write_file(path, bytes);
    EXPECT_NE(read_error(path).find("dump version 2"), std::string::npos) << read_error(path);

    bytes = good;
    put_le(bytes, 12, 0x0123456789ABCDEFull, 8);
    write_file(path, bytes);
    char expected[128];
    std::snprintf(expected, sizeof(expected),
                  "dump was written with schema hash 0123456789ABCDEF, this build has %016llX",
                  static_cast<unsigned long long>(schema_hash()));
    EXPECT_NE(read_error(path).find(expected), std::string::npos) << read_error(path);

    bytes = good;
    put_le(bytes, 20, 5000, 4);
    write_file(path, bytes);
    EXPECT_NE(read_error(path).find("5000 exceeds the limit of 4096"), std::string::npos)
        << read_error(path);

    bytes = good;
    bytes.push_back(0);
    write_file(path, bytes);
    EXPECT_NE(read_error(path).find("1 trailing bytes"), std::string::npos) << read_error(path);

    // A payload length far beyond the file: refused without allocating it.
    bytes = good;
    put_le(bytes, 24 + sample_dump().channel_name.size(), 1ull << 60, 8);
    write_file(path, bytes);
    EXPECT_NE(read_error(path).find("truncated"), std::string::npos) << read_error(path);

    EXPECT_NE(read_error(dir / "absent.dump").find("absent.dump"), std::string::npos);
    fs::remove_all(dir);
}

TEST(Dump, EveryTruncationIsRefused) {
    const fs::path dir = test::make_temp_dir("dump-truncated");
    const fs::path path = dir / "x.dump";
    ChannelDump dump = sample_dump();
    dump.payload.resize(20);
    ASSERT_TRUE(write_dump(path, dump).ok());
    const auto good = read_file(path);
    for (size_t length = 0; length < good.size(); ++length) {
        write_file(path,
                   std::vector<uint8_t>(good.begin(), good.begin() + static_cast<long>(length)));
        const std::string error = read_error(path);
        ASSERT_NE(error, "(accepted)") << "cut to " << length;
        EXPECT_NE(error.find("truncated"), std::string::npos) << length << ": " << error;
    }
    fs::remove_all(dir);
}

TEST(Dump, WriteRefusesOverlongNames) {
    const fs::path dir = test::make_temp_dir("dump-name");
    ChannelDump dump{std::string(4097, 'a'), {1, 2, 3}};
    Status status = write_dump(dir / "x.dump", dump);
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().find("4097"), std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "x.dump"));
    dump.channel_name.resize(4096);
    EXPECT_TRUE(write_dump(dir / "x.dump", dump).ok());
    EXPECT_EQ(read_dump(dir / "x.dump")->channel_name.size(), 4096u);
    fs::remove_all(dir);
}

TEST(Dump, ResultChannelSurvivesADumpRoundTrip) {
    // What `bake --record` writes and `inspect` reads.
    const fs::path dir = test::make_temp_dir("dump-result");
    LightTree tree;
    tree.nodes.resize(1);
    tree.nodes[0].guid = Guid{1, 2, 3, 4};
    tree.nodes[0].brightness = 5.0f;
    tree.nodes[0].intensity = glm::vec3(5.0f);
    tree.leaf_count = 1;
    const ChannelDump dump{lightcuts_result_channel_name(), encode_result_channel(tree)};
    const fs::path path = dump_path_for(dir, dump.channel_name);
    ASSERT_TRUE(write_dump(path, dump).ok());
    Result<ChannelDump> read = read_dump(path);
    ASSERT_TRUE(read.ok()) << read.error();
    Result<LightTree> decoded = decode_result_channel(read->payload);
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    EXPECT_EQ(decoded->nodes[0].guid, tree.nodes[0].guid);
    EXPECT_EQ(decoded->nodes[0].brightness, 5.0f);
    fs::remove_all(dir);
}

// A dump written as its payload arrives is byte for byte the dump written
// whole, and appears only at commit.
TEST(Dump, StreamedWriteMatchesTheWholeWrite) {
    const fs::path dir = test::make_temp_dir("dump-writer");
    const ChannelDump dump = sample_dump();
    ASSERT_TRUE(write_dump(dir / "whole.dump", dump).ok());
    Result<DumpWriter> writer = DumpWriter::open(dir / "streamed.dump", dump.channel_name, dump.payload.size());
    ASSERT_TRUE(writer.ok()) << writer.error();
    const std::span<const uint8_t> payload(dump.payload);
    for (size_t at = 0; at < payload.size(); at += 70) {
        ASSERT_TRUE(writer->append(payload.subspan(at, std::min<size_t>(70, payload.size() - at))).ok());
        EXPECT_FALSE(fs::exists(dir / "streamed.dump"));
    }
    ASSERT_TRUE(writer->commit().ok());
    EXPECT_EQ(read_file(dir / "streamed.dump"), read_file(dir / "whole.dump"));
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 2);
    fs::remove_all(dir);
}

// More or fewer bytes than announced, or a writer dropped before commit:
// no dump, no temporary file, and the earlier dump at the path untouched.
TEST(Dump, StreamedWriteKeepsTheOldDumpUnlessCommittedWhole) {
    const fs::path dir = test::make_temp_dir("dump-writer-refusals");
    const ChannelDump dump = sample_dump();
    const fs::path path = dir / "x.dump";
    ASSERT_TRUE(write_dump(path, dump).ok());
    const std::vector<uint8_t> before = read_file(path);
    const std::vector<uint8_t> bytes(10, 7);
    {
        Result<DumpWriter> longer = DumpWriter::open(path, "other", 9);
        ASSERT_TRUE(longer.ok());
        Status appended = longer->append(bytes);
        ASSERT_FALSE(appended.ok());
        EXPECT_NE(appended.error().find("announced 9 payload bytes"), std::string::npos) << appended.error();
        EXPECT_FALSE(longer->commit().ok());
    }
    {
        Result<DumpWriter> shorter = DumpWriter::open(path, "other", 11);
        ASSERT_TRUE(shorter.ok());
        ASSERT_TRUE(shorter->append(bytes).ok());
        Status committed = shorter->commit();
        ASSERT_FALSE(committed.ok());
        EXPECT_NE(committed.error().find("was given 10"), std::string::npos) << committed.error();
    }
    {
        Result<DumpWriter> dropped = DumpWriter::open(path, "other", 10);
        ASSERT_TRUE(dropped.ok());
        ASSERT_TRUE(dropped->append(bytes).ok());
    }
    EXPECT_EQ(read_file(path), before);
    EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
    fs::remove_all(dir);
}

}  // namespace
}  // namespace lc

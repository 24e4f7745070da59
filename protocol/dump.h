#pragma once
// Channel dumps: every byte a channel carried, in a file with a header so a
// stale or foreign dump fails loudly.
//   magic "LCDUMP01" (8 bytes), dump version (uint32), schema hash (uint64),
//   channel name length (uint32) + name bytes, payload length (uint64), payload.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include "lightcuts/result.h"

namespace lc {

inline constexpr uint32_t kDumpVersion = 1;

struct ChannelDump {
    std::string channel_name;
    std::vector<uint8_t> payload;
};

// Writes atomically (temporary file + rename).
Status write_dump(const std::filesystem::path& path, const ChannelDump& dump);

// A dump written as its payload arrives, so a channel of hundreds of
// megabytes (bake -o) goes to disk as it streams in and is never held whole.
// The payload's length is known up front (the channel's OpenChannel announces
// it). commit() checks that exactly that many bytes came, then renames into
// place as write_dump does; a writer dropped uncommitted removes its
// temporary file and leaves any earlier dump at `path` untouched.
class DumpWriter {
public:
    static Result<DumpWriter> open(const std::filesystem::path& path, const std::string& channel_name,
                                   uint64_t payload_bytes);

    DumpWriter(DumpWriter&& other) noexcept;
    DumpWriter& operator=(DumpWriter&& other) noexcept;
    DumpWriter(const DumpWriter&) = delete;
    DumpWriter& operator=(const DumpWriter&) = delete;
    ~DumpWriter();

    // Fails once more bytes come than the header announced.
    Status append(std::span<const uint8_t> bytes);
    Status commit();

private:
    DumpWriter() = default;
    Error fail(const std::string& what);
    void discard();

    std::FILE* file_ = nullptr;
    std::filesystem::path path_;
    std::filesystem::path tmp_;
    uint64_t payload_bytes_ = 0;
    uint64_t written_ = 0;
    uint64_t flushed_ = 0;  // the payload bytes handed to the disk ahead of commit's fsync
};
// Refuses wrong magic, another dump version, another schema hash (naming both
// hashes), truncated files and trailing bytes.
Result<ChannelDump> read_dump(const std::filesystem::path& path);

// A dump's header: its channel name and payload length (checked against the file).
struct DumpHeader {
    std::string channel_name;
    uint64_t payload_bytes = 0;
};

// read_dump without holding the payload whole (a million-light tree's channel
// is 380 MB): `on_header` sees the header, then `on_payload` the payload in
// chunks of at most `chunk_bytes`. The same refusals as read_dump; an error
// from either callback ends the read and is returned.
Status read_dump_streaming(const std::filesystem::path& path,
                           const std::function<Status(const DumpHeader&)>& on_header,
                           const std::function<Status(std::span<const uint8_t>)>& on_payload,
                           size_t chunk_bytes = size_t{1} << 20);

// "<dir>/<channel name>.dump": the file name --record uses for a channel.
std::filesystem::path dump_path_for(const std::filesystem::path& dir, const std::string& channel_name);

}  // namespace lc

// Channel dump files: a small header (magic, dump version, schema hash) so a
// stale or foreign dump is refused loudly, then the channel name and payload.
// All integers are little-endian.
#include "dump.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>

#include "codec.h"
#include "lightcuts/status_macros.h"

namespace lc {
namespace {

constexpr std::array<char, 8> kMagic{'L', 'C', 'D', 'U', 'M', 'P', '0', '1'};
constexpr uint32_t kMaxChannelNameBytes = 4096;
// magic + version + schema hash + name length; the payload length follows the name.
constexpr size_t kFixedHeaderBytes = 8 + 4 + 8 + 4;

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

void put_le(std::vector<uint8_t>& out, uint64_t value, int bytes) {
    for (int i = 0; i < bytes; ++i) out.push_back(static_cast<uint8_t>(value >> (8 * i)));
}

uint64_t get_le(const uint8_t* p, int bytes) {
    uint64_t value = 0;
    for (int i = bytes - 1; i >= 0; --i) value = (value << 8) | p[i];
    return value;
}

std::string hash_hex(uint64_t hash) {
    char text[24];
    std::snprintf(text, sizeof(text), "%016llX", static_cast<unsigned long long>(hash));
    return text;
}

std::string system_error(const std::string& what, const std::filesystem::path& path) {
    return what + " " + path.string() + ": " + std::strerror(errno);
}

// Reads exactly `size` bytes or reports how many the file had.
bool read_exact(std::FILE* f, uint8_t* out, size_t size) {
    return std::fread(out, 1, size, f) == size;
}

}  // namespace

Status write_dump(const std::filesystem::path& path, const ChannelDump& dump) {
    if (dump.channel_name.size() > kMaxChannelNameBytes) {
        return make_error("channel name of " + std::to_string(dump.channel_name.size()) +
                          " bytes exceeds the dump limit of " +
                          std::to_string(kMaxChannelNameBytes));
    }
    std::vector<uint8_t> header(kMagic.size());
    std::memcpy(header.data(), kMagic.data(), kMagic.size());
    put_le(header, kDumpVersion, 4);
    put_le(header, schema_hash(), 8);
    put_le(header, dump.channel_name.size(), 4);
    for (char c : dump.channel_name) header.push_back(static_cast<uint8_t>(c));
    put_le(header, dump.payload.size(), 8);

    // Readers never see a half-written dump: write a sibling file, then rename.
    static std::atomic<uint64_t> counter{0};
    std::filesystem::path tmp = path;
    tmp += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    {
        File f(std::fopen(tmp.c_str(), "wb"));
        if (!f) return make_error(system_error("cannot create", tmp));
        const bool written =
            std::fwrite(header.data(), 1, header.size(), f.get()) == header.size() &&
            (dump.payload.empty() || std::fwrite(dump.payload.data(), 1, dump.payload.size(),
                                                 f.get()) == dump.payload.size()) &&
            std::fflush(f.get()) == 0 && ::fsync(::fileno(f.get())) == 0;
        if (!written) {
            Error error = make_error(system_error("cannot write", tmp));
            f.reset();
            std::error_code ignored;
            std::filesystem::remove(tmp, ignored);
            return error;
        }
        if (std::fclose(f.release()) != 0) {
            Error error = make_error(system_error("cannot close", tmp));
            std::error_code ignored;
            std::filesystem::remove(tmp, ignored);
            return error;
        }
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        return make_error("cannot rename " + tmp.string() + " to " + path.string() + ": " +
                          ec.message());
    }
    return Ok{};
}

Status read_dump_streaming(const std::filesystem::path& path,
                           const std::function<Status(const DumpHeader&)>& on_header,
                           const std::function<Status(std::span<const uint8_t>)>& on_payload,
                           size_t chunk_bytes) {
    std::error_code ec;
    const uintmax_t file_size = std::filesystem::file_size(path, ec);
    if (ec) return make_error("cannot read dump " + path.string() + ": " + ec.message());
    File f(std::fopen(path.c_str(), "rb"));
    if (!f) return make_error(system_error("cannot open dump", path));

    std::array<uint8_t, kFixedHeaderBytes> fixed{};
    if (file_size < kFixedHeaderBytes || !read_exact(f.get(), fixed.data(), fixed.size())) {
        return make_error("dump is truncated: " + std::to_string(file_size) +
                          " bytes, shorter than its " + std::to_string(kFixedHeaderBytes) +
                          "-byte header");
    }
    if (std::memcmp(fixed.data(), kMagic.data(), kMagic.size()) != 0) {
        return make_error("not a channel dump: the file does not start with \"LCDUMP01\"");
    }
    const auto version = static_cast<uint32_t>(get_le(fixed.data() + 8, 4));
    if (version != kDumpVersion) {
        return make_error("dump version " + std::to_string(version) +
                          " is not supported; this build reads version " +
                          std::to_string(kDumpVersion));
    }
    const uint64_t hash = get_le(fixed.data() + 12, 8);
    if (hash != schema_hash()) {
        return make_error("dump was written with schema hash " + hash_hex(hash) +
                          ", this build has " + hash_hex(schema_hash()));
    }
    const auto name_bytes = static_cast<uint32_t>(get_le(fixed.data() + 20, 4));
    if (name_bytes > kMaxChannelNameBytes) {
        return make_error("dump channel name length " + std::to_string(name_bytes) +
                          " exceeds the limit of " + std::to_string(kMaxChannelNameBytes));
    }
    const uint64_t after_fixed = file_size - kFixedHeaderBytes;
    if (after_fixed < name_bytes + uint64_t{8}) {
        return make_error("dump is truncated inside its channel name or payload length");
    }
    DumpHeader header;
    header.channel_name.resize(name_bytes);
    std::array<uint8_t, 8> length_bytes{};
    if (!read_exact(f.get(), reinterpret_cast<uint8_t*>(header.channel_name.data()), name_bytes) ||
        !read_exact(f.get(), length_bytes.data(), length_bytes.size())) {
        return make_error(system_error("cannot read dump header of", path));
    }
    const uint64_t payload_bytes = get_le(length_bytes.data(), 8);
    // The header's length is checked against the file before anything is allocated.
    const uint64_t available = after_fixed - name_bytes - 8;
    if (payload_bytes > available) {
        return make_error("dump is truncated: header announces " + std::to_string(payload_bytes) +
                          " payload bytes, the file holds " + std::to_string(available));
    }
    if (payload_bytes < available) {
        return make_error("dump has " + std::to_string(available - payload_bytes) +
                          " trailing bytes after its " + std::to_string(payload_bytes) +
                          "-byte payload");
    }
    header.payload_bytes = payload_bytes;
    LC_RETURN_IF_ERROR(on_header(header));
    std::vector<uint8_t> chunk(static_cast<size_t>(std::min<uint64_t>(payload_bytes, chunk_bytes)));
    for (uint64_t done = 0; done < payload_bytes;) {
        const size_t n = static_cast<size_t>(std::min<uint64_t>(chunk.size(), payload_bytes - done));
        if (!read_exact(f.get(), chunk.data(), n)) {
            return make_error(system_error("cannot read dump payload of", path));
        }
        LC_RETURN_IF_ERROR(on_payload(std::span<const uint8_t>(chunk.data(), n)));
        done += n;
    }
    return Ok{};
}

Result<ChannelDump> read_dump(const std::filesystem::path& path) {
    ChannelDump dump;
    Status read = read_dump_streaming(
        path,
        [&](const DumpHeader& header) -> Status {
            dump.channel_name = header.channel_name;
            dump.payload.reserve(static_cast<size_t>(header.payload_bytes));
            return Ok{};
        },
        [&](std::span<const uint8_t> chunk) -> Status {
            dump.payload.insert(dump.payload.end(), chunk.begin(), chunk.end());
            return Ok{};
        });
    if (!read) return read.failure();
    return dump;
}

std::filesystem::path dump_path_for(const std::filesystem::path& dir,
                                    const std::string& channel_name) {
    return dir / (channel_name + ".dump");
}

}  // namespace lc

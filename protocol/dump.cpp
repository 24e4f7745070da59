// Channel dump files: a small header (magic, dump version, schema hash) so a
// stale or foreign dump is refused loudly, then the channel name and payload.
// All integers are little-endian.
#include "dump.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <utility>

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
    Result<DumpWriter> writer = DumpWriter::open(path, dump.channel_name, dump.payload.size());
    if (!writer) return writer.failure();
    LC_RETURN_IF_ERROR(writer->append(dump.payload));
    return writer->commit();
}

Result<DumpWriter> DumpWriter::open(const std::filesystem::path& path, const std::string& channel_name,
                                    uint64_t payload_bytes) {
    if (channel_name.size() > kMaxChannelNameBytes) {
        return make_error("channel name of " + std::to_string(channel_name.size()) +
                          " bytes exceeds the dump limit of " + std::to_string(kMaxChannelNameBytes));
    }
    std::vector<uint8_t> header(kMagic.size());
    std::memcpy(header.data(), kMagic.data(), kMagic.size());
    put_le(header, kDumpVersion, 4);
    put_le(header, schema_hash(), 8);
    put_le(header, channel_name.size(), 4);
    for (char c : channel_name) header.push_back(static_cast<uint8_t>(c));
    put_le(header, payload_bytes, 8);

    // Readers never see a half-written dump: write a sibling file, then rename.
    static std::atomic<uint64_t> counter{0};
    DumpWriter writer;
    writer.path_ = path;
    writer.tmp_ = path;
    writer.tmp_ += ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
    writer.payload_bytes_ = payload_bytes;
    writer.file_ = std::fopen(writer.tmp_.c_str(), "wb");
    if (!writer.file_) return make_error(system_error("cannot create", writer.tmp_));
    if (std::fwrite(header.data(), 1, header.size(), writer.file_) != header.size()) {
        return writer.fail("cannot write");
    }
    return writer;
}

DumpWriter::DumpWriter(DumpWriter&& other) noexcept
    : file_(std::exchange(other.file_, nullptr)),
      path_(std::move(other.path_)),
      tmp_(std::move(other.tmp_)),
      payload_bytes_(other.payload_bytes_),
      written_(other.written_),
      flushed_(other.flushed_) {}

DumpWriter& DumpWriter::operator=(DumpWriter&& other) noexcept {
    if (this != &other) {
        discard();
        file_ = std::exchange(other.file_, nullptr);
        path_ = std::move(other.path_);
        tmp_ = std::move(other.tmp_);
        payload_bytes_ = other.payload_bytes_;
        written_ = other.written_;
        flushed_ = other.flushed_;
    }
    return *this;
}

DumpWriter::~DumpWriter() { discard(); }

void DumpWriter::discard() {
    if (!file_) return;
    std::fclose(file_);
    file_ = nullptr;
    std::error_code ignored;
    std::filesystem::remove(tmp_, ignored);
}

Error DumpWriter::fail(const std::string& what) {
    Error error = make_error(system_error(what, tmp_));
    discard();
    return error;
}

Status DumpWriter::append(std::span<const uint8_t> bytes) {
    if (!file_) return make_error("dump " + path_.string() + " is closed");
    if (bytes.size() > payload_bytes_ - written_) {
        discard();
        return make_error("dump " + path_.string() + " announced " + std::to_string(payload_bytes_) +
                          " payload bytes and was given more");
    }
    if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), file_) != bytes.size()) {
        return fail("cannot write");
    }
    written_ += bytes.size();
    // Start the disk on what has come so far, so that commit's fsync waits for
    // the last stretch only rather than the whole payload.
    constexpr uint64_t kWriteBehindBytes = uint64_t{16} << 20;
    if (written_ - flushed_ >= kWriteBehindBytes) {
        if (std::fflush(file_) != 0) return fail("cannot write");
        ::sync_file_range(::fileno(file_), 0, 0, SYNC_FILE_RANGE_WRITE);
        flushed_ = written_;
    }
    return Ok{};
}

Status DumpWriter::commit() {
    if (!file_) return make_error("dump " + path_.string() + " is closed");
    if (written_ != payload_bytes_) {
        discard();
        return make_error("dump " + path_.string() + " announced " + std::to_string(payload_bytes_) +
                          " payload bytes and was given " + std::to_string(written_));
    }
    if (std::fflush(file_) != 0 || ::fsync(::fileno(file_)) != 0) return fail("cannot write");
    const int closed = std::fclose(file_);
    file_ = nullptr;
    std::error_code ec;
    if (closed != 0) {
        Error error = make_error(system_error("cannot close", tmp_));
        std::filesystem::remove(tmp_, ec);
        return error;
    }
    std::filesystem::rename(tmp_, path_, ec);
    if (ec) {
        std::error_code ignored;
        std::filesystem::remove(tmp_, ignored);
        return make_error("cannot rename " + tmp_.string() + " to " + path_.string() + ": " + ec.message());
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

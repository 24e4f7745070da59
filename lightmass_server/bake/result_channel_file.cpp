#include "lightmass_server/bake/result_channel_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

#include "protocol/channel_records.h"
#include "protocol/codec.h"

namespace lc::bake {
namespace fs = std::filesystem;

ResultChannelFile::ResultChannelFile(fs::path path) : path_(std::move(path)) {
    fd_ = ::open(path_.c_str(), O_RDONLY | O_CLOEXEC);
}

ResultChannelFile::~ResultChannelFile() {
    if (fd_ >= 0) ::close(fd_);
    std::error_code ec;
    fs::remove(path_, ec);
}

Result<std::shared_ptr<const ResultChannelFile>> ResultChannelFile::adopt(const fs::path& path) {
    std::shared_ptr<ResultChannelFile> file(new ResultChannelFile(path));
    if (file->fd_ < 0) return make_error("cannot open " + path.string() + ": " + std::strerror(errno));
    Status valid = file->validate();
    if (!valid) return make_error(path.filename().string() + ": " + valid.error());
    return std::shared_ptr<const ResultChannelFile>(std::move(file));
}

Status ResultChannelFile::read(uint64_t offset, std::span<uint8_t> out) const {
    size_t done = 0;
    while (done < out.size()) {
        const ssize_t got = ::pread(fd_, out.data() + done, out.size() - done, off_t(offset + done));
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) return make_error("cannot read " + path_.string() + ": " + std::strerror(errno));
        if (got == 0)
            return make_error(path_.string() + " ends at byte " + std::to_string(offset + done) + ", before " +
                              std::to_string(offset + out.size()));
        done += size_t(got);
    }
    return Ok{};
}

// One pass a chunk at a time through the channel's reader, keeping only the links.
Status ResultChannelFile::validate() {
    ResultChannelReader reader(TreeImport::kValidateOnly);
    std::vector<uint8_t> chunk(kDefaultChunkBytes);
    for (;;) {
        const ssize_t got = ::pread(fd_, chunk.data(), chunk.size(), off_t(size_bytes_));
        if (got < 0 && errno == EINTR) continue;
        if (got < 0) return make_error(std::string("cannot read: ") + std::strerror(errno));
        if (got == 0) break;
        Status consumed = reader.consume(std::span(chunk.data(), size_t(got)));
        if (!consumed) return consumed;
        size_bytes_ += uint64_t(got);
    }
    Status valid = reader.finish_validation();
    if (!valid) return valid;
    node_count_ = uint32_t(reader.nodes_expected());
    leaf_count_ = reader.leaf_count();
    return Ok{};
}

}  // namespace lc::bake

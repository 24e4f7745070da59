#include "editor_client/scene/inputs/mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <utility>

namespace lc::client {
namespace {

constexpr off_t kMaxMappedBytes = off_t(1) << 32;

struct FileDescriptor {
    int fd = -1;
    ~FileDescriptor() {
        if (fd >= 0) ::close(fd);
    }
};

}  // namespace

Result<MappedFile> MappedFile::open(const std::filesystem::path& path) {
    FileDescriptor file{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
    if (file.fd < 0) return make_error("cannot open '" + path.string() + "': " + std::strerror(errno));
    struct stat info {};
    if (::fstat(file.fd, &info) != 0 || !S_ISREG(info.st_mode)) {
        return make_error("'" + path.string() + "' is not a regular file");
    }
    if (info.st_size > kMaxMappedBytes) return make_error("'" + path.string() + "' is larger than 4 GiB");
    if (info.st_size == 0) return MappedFile(nullptr, 0);
    void* data = ::mmap(nullptr, size_t(info.st_size), PROT_READ, MAP_PRIVATE, file.fd, 0);
    if (data == MAP_FAILED) {
        return make_error("cannot map '" + path.string() + "': " + std::strerror(errno));
    }
    // Read front to back once: the kernel may read ahead further and drop behind.
    ::madvise(data, size_t(info.st_size), MADV_SEQUENTIAL);
    return MappedFile(static_cast<const uint8_t*>(data), size_t(info.st_size));
}

MappedFile::MappedFile(MappedFile&& other) noexcept
    : data_(std::exchange(other.data_, nullptr)),
      size_(std::exchange(other.size_, 0)),
      released_(std::exchange(other.released_, 0)) {}

MappedFile& MappedFile::operator=(MappedFile&& other) noexcept {
    if (this != &other) {
        if (data_) ::munmap(const_cast<uint8_t*>(data_), size_);
        data_ = std::exchange(other.data_, nullptr);
        size_ = std::exchange(other.size_, 0);
        released_ = std::exchange(other.released_, 0);
    }
    return *this;
}

MappedFile::~MappedFile() {
    if (data_) ::munmap(const_cast<uint8_t*>(data_), size_);
}

void MappedFile::release_before(size_t offset) {
    static const size_t page = size_t(::sysconf(_SC_PAGESIZE));
    const size_t end = std::min(offset, size_) / page * page;
    if (end <= released_) return;
    // MADV_DONTNEED on a private, unwritten file mapping: the pages leave the
    // resident set and are read again from the page cache if touched.
    ::madvise(const_cast<uint8_t*>(data_) + released_, end - released_, MADV_DONTNEED);
    released_ = end;
}

}  // namespace lc::client

#pragma once
// A regular file mapped read-only, for a scene file of hundreds of megabytes:
// its pages come from the page cache as the loader reads them, and
// release_before() hands back the ones the loader is done with, so the file
// never counts against the client's memory all at once. The same checks as
// GltfResourceAccess::read_regular_file: opened non-blocking (a FIFO never
// blocks), a regular file, at most 4 GiB.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>

#include "lightcuts/result.h"

namespace lc::client {

class MappedFile {
public:
    static Result<MappedFile> open(const std::filesystem::path& path);

    MappedFile(MappedFile&& other) noexcept;
    MappedFile& operator=(MappedFile&& other) noexcept;
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;
    ~MappedFile();

    std::span<const uint8_t> bytes() const { return {data_, size_}; }
    // The bytes before `offset` will not be read soon: their pages leave this
    // process's memory (they stay readable; a later read brings them back).
    void release_before(size_t offset);

private:
    MappedFile(const uint8_t* data, size_t size) : data_(data), size_(size) {}

    const uint8_t* data_ = nullptr;
    size_t size_ = 0;
    size_t released_ = 0;  // whole pages before this offset are released
};

}  // namespace lc::client

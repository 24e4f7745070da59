#pragma once
// A finished tree as the result channel's bytes in a file, for a tree built
// in other processes (an MPI bake's rank 0 writes one: mpi/rank_job.h). The
// server checks it a chunk at a time when it adopts it (every record, then
// the structure on the links alone: at most 25 bytes a node, never the
// decoded tree), and the result stream then copies its chunks to the client:
// the file is the channel's bytes, so a chunk at channel offset X is the
// file's bytes at X. The file is removed when the last owner lets it go.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>

#include "lightcuts/result.h"

namespace lc::bake {

class ResultChannelFile {
public:
    // Takes `path` over (removed whatever the outcome); an error names what is wrong in it.
    static Result<std::shared_ptr<const ResultChannelFile>> adopt(const std::filesystem::path& path);
    ~ResultChannelFile();
    ResultChannelFile(const ResultChannelFile&) = delete;
    ResultChannelFile& operator=(const ResultChannelFile&) = delete;

    uint32_t node_count() const { return node_count_; }
    uint32_t leaf_count() const { return leaf_count_; }
    uint64_t size_bytes() const { return size_bytes_; }
    // Fills `out` with the bytes from `offset`; thread-safe.
    Status read(uint64_t offset, std::span<uint8_t> out) const;

private:
    explicit ResultChannelFile(std::filesystem::path path);
    Status validate();

    std::filesystem::path path_;
    int fd_ = -1;
    uint64_t size_bytes_ = 0;
    uint32_t node_count_ = 0;
    uint32_t leaf_count_ = 0;
};

}  // namespace lc::bake

#pragma once
// The byteLength of each buffer a glTF reads from a file, read from its JSON
// before the file is: the loader compares the file's size with it first, so
// a buffer of byteLength 912 naming a 2 GB file is refused by its size, not
// after reading 2 GB (issue 27).
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace lc::client {

struct BufferFileSize {
    std::string uri;  // as written (not a data: URI)
    uint64_t byte_length = 0;
};

// The .gltf text or .glb bytes; nothing for a document that does not parse
// (the loader then reports what is wrong with it).
std::vector<BufferFileSize> external_buffer_sizes(std::span<const uint8_t> gltf);

}  // namespace lc::client

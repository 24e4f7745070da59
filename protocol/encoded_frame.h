#pragma once
// A frame built in place: FlatBuffers writes a body back to front, from the
// end of its buffer, and the size prefix goes into the bytes left in front of
// the body. The frame is the body's own buffer, so a 1 MiB WriteChannel is
// not copied once more to put four bytes before it (codec.h makes these).
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>

namespace lc {

class EncodedFrame {
public:
    // `storage` holds the frame at [begin, begin + size).
    EncodedFrame(std::unique_ptr<uint8_t[]> storage, size_t begin, size_t size)
        : storage_(std::move(storage)), begin_(begin), size_(size) {}

    // The size prefix and the body, as they go on the wire.
    std::span<const uint8_t> bytes() const { return {storage_.get() + begin_, size_}; }

private:
    std::unique_ptr<uint8_t[]> storage_;
    size_t begin_;
    size_t size_;
};

}  // namespace lc

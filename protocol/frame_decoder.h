#pragma once
// Framing: every frame is a little-endian uint32 byte count followed by that
// many bytes (one FlatBuffers Envelope). The decoder is a push parser so it can
// be tested without sockets; the size cap is checked before any allocation.
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace lc {

inline constexpr uint32_t kDefaultMaxFrameBytes = 16u << 20;  // 16 MiB
inline constexpr size_t kFrameHeaderBytes = 4;

class FrameDecoder {
public:
    enum class State { kReadingHeader, kReadingBody, kFailed };

    explicit FrameDecoder(uint32_t max_frame_bytes = kDefaultMaxFrameBytes);

    // Pushes bytes in; complete frames are appended to `frames`. Returns false
    // (and stays failed) when a header announces a frame larger than the cap or
    // an empty frame; error() then names the problem.
    bool consume(std::span<const uint8_t> bytes, std::vector<std::vector<uint8_t>>& frames);

    // The same parser for a reader that reads the socket straight into the
    // frame: read_buffer() is where the next read should land (the rest of the
    // header, or up to `max_bytes` of the body being read), commit(n) accepts
    // the first n bytes written there. A body is sized to what the reads ask
    // for, never to what a header announces. Empty while failed.
    std::span<uint8_t> read_buffer(size_t max_bytes);
    bool commit(size_t n, std::vector<std::vector<uint8_t>>& frames);
    // Hands a frame's storage back once its message is handled: the next body
    // reuses it instead of faulting in new pages.
    void recycle(std::vector<uint8_t>&& frame);

    State state() const { return state_; }
    const std::string& error() const { return error_; }
    // Bytes of a partial frame held right now (header or body).
    size_t buffered_bytes() const;

private:
    void start_body();
    void fail(std::string error);

    uint32_t max_frame_bytes_;
    State state_ = State::kReadingHeader;
    uint8_t header_[kFrameHeaderBytes] = {};
    size_t header_filled_ = 0;
    uint32_t body_expected_ = 0;
    std::vector<uint8_t> body_;
    size_t body_filled_ = 0;
    std::vector<uint8_t> spare_;  // a handled frame's storage, for the next body
    std::string error_;
};

// Prepends the size header to an encoded frame body.
std::vector<uint8_t> frame_bytes(std::span<const uint8_t> body);
// Writes the size header of a `body_size`-byte body to `out`.
void put_frame_header(size_t body_size, uint8_t* out);

}  // namespace lc

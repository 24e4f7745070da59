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

    State state() const { return state_; }
    const std::string& error() const { return error_; }
    // Bytes of a partial frame held right now (header or body).
    size_t buffered_bytes() const;

private:
    uint32_t max_frame_bytes_;
    State state_ = State::kReadingHeader;
    uint8_t header_[kFrameHeaderBytes] = {};
    size_t header_filled_ = 0;
    std::vector<uint8_t> body_;
    size_t body_filled_ = 0;
    std::string error_;
};

// Prepends the size header to an encoded frame body.
std::vector<uint8_t> frame_bytes(std::span<const uint8_t> body);
// Writes the size header of a `body_size`-byte body to `out`.
void put_frame_header(size_t body_size, uint8_t* out);

}  // namespace lc

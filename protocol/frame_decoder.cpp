// Push parser for size-prefixed frames. The announced size is checked against
// the cap before any memory is reserved, and the body grows only as bytes
// actually arrive, so a lying header cannot make us allocate the cap.
#include "frame_decoder.h"

#include <algorithm>
#include <stdexcept>

namespace lc {
namespace {

// Up-front reservation for a body; larger bodies grow as their bytes arrive,
// to at most this many times the bytes that arrived: a lying header still costs
// little, and a 1 MiB chunk read 256 KiB at a time is copied once, not regrown
// four times.
constexpr size_t kInitialBodyReserve = 64u * 1024u;
constexpr size_t kReserveArrivedFactor = 8;

uint32_t read_u32_le(const uint8_t* p) {
    return static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) |
           (static_cast<uint32_t>(p[2]) << 16) | (static_cast<uint32_t>(p[3]) << 24);
}

}  // namespace

FrameDecoder::FrameDecoder(uint32_t max_frame_bytes) : max_frame_bytes_(max_frame_bytes) {}

size_t FrameDecoder::buffered_bytes() const {
    switch (state_) {
        case State::kReadingHeader: return header_filled_;
        case State::kReadingBody: return kFrameHeaderBytes + body_filled_;
        case State::kFailed: return 0;
    }
    return 0;
}

bool FrameDecoder::consume(std::span<const uint8_t> bytes,
                           std::vector<std::vector<uint8_t>>& frames) {
    size_t pos = 0;
    while (state_ != State::kFailed && pos < bytes.size()) {
        if (state_ == State::kReadingHeader) {
            const size_t take = std::min(kFrameHeaderBytes - header_filled_, bytes.size() - pos);
            std::copy_n(bytes.data() + pos, take, header_ + header_filled_);
            header_filled_ += take;
            pos += take;
            if (header_filled_ < kFrameHeaderBytes) break;

            const uint32_t size = read_u32_le(header_);
            if (size == 0) {
                error_ = "malformed frame: header announces an empty frame (0 bytes)";
                state_ = State::kFailed;
                break;
            }
            if (size > max_frame_bytes_) {
                error_ = "malformed frame: header announces " + std::to_string(size) +
                         " bytes, above the limit of " + std::to_string(max_frame_bytes_) +
                         " bytes";
                state_ = State::kFailed;
                break;
            }
            body_.clear();
            body_.reserve(std::min<size_t>(size, kInitialBodyReserve));
            body_filled_ = 0;
            state_ = State::kReadingBody;
            continue;
        }

        // kReadingBody
        const size_t expected = read_u32_le(header_);
        const size_t take = std::min(expected - body_filled_, bytes.size() - pos);
        if (body_.capacity() < body_filled_ + take) {
            body_.reserve(std::min(expected, kReserveArrivedFactor * (body_filled_ + take)));
        }
        body_.insert(body_.end(), bytes.data() + pos, bytes.data() + pos + take);
        body_filled_ += take;
        pos += take;
        if (body_filled_ == expected) {
            frames.push_back(std::move(body_));
            body_ = {};
            body_filled_ = 0;
            header_filled_ = 0;
            state_ = State::kReadingHeader;
        }
    }
    if (state_ == State::kFailed) {
        // Nothing more is parsed on this connection; release what we held.
        body_ = {};
        body_filled_ = 0;
        header_filled_ = 0;
        return false;
    }
    return true;
}

std::vector<uint8_t> frame_bytes(std::span<const uint8_t> body) {
    std::vector<uint8_t> out;
    out.reserve(kFrameHeaderBytes + body.size());
    out.resize(kFrameHeaderBytes);
    put_frame_header(body.size(), out.data());
    out.insert(out.end(), body.begin(), body.end());
    return out;
}

void put_frame_header(size_t body_size, uint8_t* out) {
    if (body_size > UINT32_MAX) throw std::length_error("frame body does not fit a uint32 size");
    const auto size = static_cast<uint32_t>(body_size);
    for (size_t i = 0; i < kFrameHeaderBytes; ++i) out[i] = static_cast<uint8_t>(size >> (8 * i));
}

}  // namespace lc

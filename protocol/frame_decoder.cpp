// Push parser for size-prefixed frames. The announced size is checked against
// the cap before any memory is reserved, and the body grows only as reads ask
// for room, so a lying header cannot make us allocate the cap.
#include "frame_decoder.h"

#include <algorithm>
#include <stdexcept>

namespace lc {
namespace {

// Up-front reservation for a body; larger bodies grow as reads ask for room,
// to at most this many times the bytes that arrived (or one read's room): a
// lying header still costs little, and a 1 MiB chunk read 256 KiB at a time
// is copied once, not regrown four times.
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
        const std::span<uint8_t> into = read_buffer(bytes.size() - pos);
        std::copy_n(bytes.data() + pos, into.size(), into.data());
        pos += into.size();
        commit(into.size(), frames);
    }
    return state_ != State::kFailed;
}

std::span<uint8_t> FrameDecoder::read_buffer(size_t max_bytes) {
    if (state_ == State::kReadingHeader) {
        return {header_ + header_filled_, std::min(kFrameHeaderBytes - header_filled_, max_bytes)};
    }
    if (state_ == State::kFailed) return {};
    const size_t end = std::min<size_t>(body_expected_, body_filled_ + max_bytes);
    if (body_.size() < end) {
        if (body_.capacity() < end) {
            body_.reserve(
                std::min<size_t>(body_expected_, std::max(end, kReserveArrivedFactor * body_filled_)));
        }
        body_.resize(end);
    }
    return {body_.data() + body_filled_, end - body_filled_};
}

bool FrameDecoder::commit(size_t n, std::vector<std::vector<uint8_t>>& frames) {
    if (state_ == State::kReadingHeader) {
        if (n > kFrameHeaderBytes - header_filled_)
            throw std::out_of_range("FrameDecoder: commit past the header");
        header_filled_ += n;
        if (header_filled_ == kFrameHeaderBytes) start_body();
    } else if (state_ == State::kReadingBody) {
        if (body_filled_ + n > std::min<size_t>(body_.size(), body_expected_)) {
            throw std::out_of_range("FrameDecoder: commit past the read buffer");
        }
        body_filled_ += n;
        if (body_filled_ == body_expected_) {
            body_.resize(body_expected_);
            frames.push_back(std::move(body_));
            body_ = std::vector<uint8_t>();
            body_filled_ = 0;
            header_filled_ = 0;
            state_ = State::kReadingHeader;
        }
    }
    return state_ != State::kFailed;
}

void FrameDecoder::recycle(std::vector<uint8_t>&& frame) {
    if (state_ != State::kFailed && frame.capacity() > spare_.capacity()) spare_ = std::move(frame);
}

void FrameDecoder::start_body() {
    const uint32_t size = read_u32_le(header_);
    if (size == 0) return fail("malformed frame: header announces an empty frame (0 bytes)");
    if (size > max_frame_bytes_) {
        return fail("malformed frame: header announces " + std::to_string(size) +
                    " bytes, above the limit of " + std::to_string(max_frame_bytes_) + " bytes");
    }
    body_expected_ = size;
    // A recycled frame keeps its size: the bytes a read lands on are not
    // zeroed first. Its capacity was a real frame's, not this header's word.
    body_ = std::move(spare_);
    spare_ = std::vector<uint8_t>();
    if (body_.capacity() == 0) body_.reserve(std::min<size_t>(size, kInitialBodyReserve));
    body_filled_ = 0;
    state_ = State::kReadingBody;
}

void FrameDecoder::fail(std::string error) {
    error_ = std::move(error);
    state_ = State::kFailed;
    // Nothing more is parsed on this connection; release what we held.
    body_ = std::vector<uint8_t>();
    spare_ = std::vector<uint8_t>();
    body_filled_ = 0;
    header_filled_ = 0;
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

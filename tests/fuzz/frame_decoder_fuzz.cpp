// FrameDecoder: any byte stream, pushed whole or in pieces of any size, gives
// the same frames and the same verdict, also read straight into the frame
// (read_buffer, commit) with each handled frame's storage recycled; every frame is within the cap; framing
// the frames again reproduces exactly the bytes they came from.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "fuzz_check.h"
#include "protocol/frame_decoder.h"

namespace {
// A small cap keeps the fuzzer's inputs able to reach it.
constexpr uint32_t kMaxFrameBytes = 1u << 16;
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using lc::fuzz::check;
    if (size == 0) return 0;
    const size_t stride = size_t(data[0] % 19) + 1;  // the first byte picks the piece size
    const std::span<const uint8_t> input(data + 1, size - 1);

    lc::FrameDecoder whole(kMaxFrameBytes);
    lc::FrameDecoder pieces(kMaxFrameBytes);
    std::vector<std::vector<uint8_t>> whole_frames;
    std::vector<std::vector<uint8_t>> piece_frames;
    const bool whole_ok = whole.consume(input, whole_frames);
    bool pieces_ok = true;
    for (size_t at = 0; at < input.size() && pieces_ok; at += stride) {
        pieces_ok = pieces.consume(input.subspan(at, std::min(stride, input.size() - at)),
                                   piece_frames);
    }
    check(whole_ok == pieces_ok, "the verdict does not depend on how the bytes arrive");

    lc::FrameDecoder reader(kMaxFrameBytes);
    std::vector<std::vector<uint8_t>> read_frames;
    std::vector<std::vector<uint8_t>> ready;
    bool read_ok = true;
    for (size_t at = 0; at < input.size() && read_ok;) {
        const std::span<uint8_t> into = reader.read_buffer(stride);
        const size_t n = std::min(into.size(), input.size() - at);
        std::copy_n(input.data() + at, n, into.data());
        at += n;
        ready.clear();
        read_ok = reader.commit(n, ready);
        for (std::vector<uint8_t>& frame : ready) {
            read_frames.push_back(frame);
            reader.recycle(std::move(frame));
        }
    }
    check(read_ok == whole_ok, "reading into the frame gives the same verdict");
    check(read_frames == whole_frames, "reading into the frame gives the same frames");
    check(whole_frames == piece_frames, "the frames do not depend on how the bytes arrive");
    check(whole_ok == (whole.state() != lc::FrameDecoder::State::kFailed),
          "consume() returns false exactly when the decoder failed");
    check(whole_ok || !whole.error().empty(), "a failed decoder says why");

    std::vector<uint8_t> reframed;
    for (const std::vector<uint8_t>& frame : whole_frames) {
        check(!frame.empty() && frame.size() <= kMaxFrameBytes, "frames are within (0, cap]");
        const std::vector<uint8_t> bytes = lc::frame_bytes(frame);
        reframed.insert(reframed.end(), bytes.begin(), bytes.end());
    }
    check(reframed.size() <= input.size() &&
              std::equal(reframed.begin(), reframed.end(), input.begin()),
          "framing the frames again gives the bytes they came from");
    if (whole_ok) {
        check(reframed.size() + whole.buffered_bytes() == input.size(),
              "every byte is in a frame or in the partial frame held");
    }
    return 0;
}

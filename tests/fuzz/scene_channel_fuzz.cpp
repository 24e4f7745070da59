// Scene channel reader: any payload, pushed whole or in pieces, gives the same
// verdict and lights; what decodes encodes back to exactly the input (every
// byte of a record is a field or a reserved zero).
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "fuzz_check.h"
#include "protocol/channel_records.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using lc::fuzz::check;
    if (size == 0) return 0;
    const size_t stride = size_t(data[0]) * 7 + 1;  // the first byte picks the piece size
    const std::span<const uint8_t> input(data + 1, size - 1);

    lc::Result<std::vector<lc::SceneLight>> whole = lc::decode_scene_channel(input);
    lc::SceneChannelReader reader;
    bool pieces_ok = true;
    for (size_t at = 0; at < input.size() && pieces_ok; at += stride) {
        pieces_ok = reader.consume(input.subspan(at, std::min(stride, input.size() - at))).ok();
    }
    lc::Result<std::vector<lc::SceneLight>> pieces =
        pieces_ok ? reader.finish() : lc::Result<std::vector<lc::SceneLight>>(lc::make_error("refused"));
    check(whole.ok() == pieces.ok(), "the verdict does not depend on how the bytes arrive");
    if (!whole) return 0;

    const std::vector<uint8_t> encoded = lc::encode_scene_channel(*whole);
    check(encoded == lc::encode_scene_channel(*pieces), "whole and pieces give the same lights");
    check(std::equal(encoded.begin(), encoded.end(), input.begin(), input.end()),
          "encode(decode(x)) == x");
    return 0;
}

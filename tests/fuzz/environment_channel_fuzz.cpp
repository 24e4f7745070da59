// Environment channel reader (an untrusted map or sun and sky from a client):
// any payload, pushed whole or in pieces, gives the same verdict and the same
// environment, and what decodes passes the environment's own validation.
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "fuzz_check.h"
#include "protocol/environment_records.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using lc::fuzz::check;
    if (size == 0) return 0;
    const size_t stride = size_t(data[0]) * 7 + 1;  // the first byte picks the piece size
    const std::span<const uint8_t> input(data + 1, size - 1);

    lc::Result<lc::Environment> whole = lc::decode_environment_channel(input);
    lc::EnvironmentChannelReader reader;
    bool pieces_ok = true;
    for (size_t at = 0; at < input.size() && pieces_ok; at += stride) {
        pieces_ok = reader.consume(input.subspan(at, std::min(stride, input.size() - at))).ok();
    }
    lc::Result<lc::Environment> pieces =
        pieces_ok ? reader.finish() : lc::Result<lc::Environment>(lc::make_error("refused"));
    check(whole.ok() == pieces.ok(), "the verdict does not depend on how the bytes arrive");
    if (!whole) return 0;

    check(lc::validate_environment(*whole).ok(), "what decodes is a valid environment");
    const std::vector<uint8_t> encoded = lc::encode_environment_channel(*whole);
    check(encoded == lc::encode_environment_channel(*pieces), "whole and pieces give the same environment");
    return 0;
}

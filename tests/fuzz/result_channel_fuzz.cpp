// Result channel reader: any payload, pushed whole or in pieces, gives the same
// verdict, with the nodes kept or only validated (bake's reader); decode,
// encode and decode again agree (issue 14, item 5: a node the
// encoder cannot write finitely must be refused at the first decode).
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "fuzz_check.h"
#include "protocol/channel_records.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using lc::fuzz::check;
    if (size == 0) return 0;
    const size_t stride = size_t(data[0]) * 13 + 1;  // the first byte picks the piece size
    const std::span<const uint8_t> input(data + 1, size - 1);

    lc::Result<lc::LightTree> whole = lc::decode_result_channel(input);
    lc::ResultChannelReader reader;
    bool pieces_ok = true;
    for (size_t at = 0; at < input.size() && pieces_ok; at += stride) {
        pieces_ok = reader.consume(input.subspan(at, std::min(stride, input.size() - at))).ok();
    }
    const bool pieces_decoded = pieces_ok && reader.finish().ok();
    check(whole.ok() == pieces_decoded, "the verdict does not depend on how the bytes arrive");
    lc::ResultChannelReader validator(lc::TreeImport::kValidateOnly);
    lc::Status validated = validator.consume(input);
    if (validated) validated = validator.finish_validation();
    check(whole.ok() == validated.ok(), "validating without keeping nodes gives the same verdict");
    if (!whole) return 0;

    check(lc::validate_tree(*whole).ok(), "a decoded tree is valid");
    const std::vector<uint8_t> encoded = lc::encode_result_channel(*whole);
    lc::Result<lc::LightTree> again = lc::decode_result_channel(encoded);
    check(again.ok(), "decode(encode(decode(x))) succeeds");
    check(again->leaf_count == whole->leaf_count, "the leaf count survives a round trip");
    check(lc::encode_result_channel(*again) == encoded, "decode and decode again agree");
    return 0;
}

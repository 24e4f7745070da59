// Message decoding: any frame body decodes or is refused without a crash; what
// decodes encodes to a body that decodes again to the same encoding.
#include <cstdint>
#include <span>
#include <vector>

#include "fuzz_check.h"
#include "protocol/bake_limits.h"
#include "protocol/codec.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using lc::fuzz::check;
    lc::Result<lc::Message> message = lc::decode_message(std::span(data, size));
    if (!message) {
        check(!message.error().empty(), "a refused body says why");
        return 0;
    }
    // Any settings a request may carry are judged, with a reason when refused (issue 27).
    if (const auto* request = std::get_if<lc::BakeRequestMsg>(&*message)) {
        lc::Status settings = lc::validate_bake_settings(*request);
        check(settings.ok() || !settings.error().empty(), "a refused bake request says why");
    }
    const std::vector<uint8_t> body = lc::encode_message(*message);
    lc::Result<lc::Message> again = lc::decode_message(body);
    check(again.ok(), "an encoded message decodes");
    check(again->index() == message->index(), "the message kind survives a round trip");
    check(lc::encode_message(*again) == body, "decode(encode(m)) encodes to the same bytes");
    return 0;
}

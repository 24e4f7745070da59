#pragma once
// Encodes our Message types to FlatBuffers Envelopes and back. Decoding runs the
// FlatBuffers Verifier (with depth/table limits and the frame's own size) and
// then checks enum ranges and required fields; nothing is read before that.
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "encoded_frame.h"
#include "messages.h"
#include "lightcuts/result.h"

namespace lc {

// The FlatBuffers body of a frame (no size prefix); file identifier "LCP1".
std::vector<uint8_t> encode_message(const Message& message);
// The full frame: size prefix + body.
std::vector<uint8_t> encode_frame(const Message& message);
// The same bytes as encode_frame, built in place (encoded_frame.h).
EncodedFrame encode_frame_in_place(const Message& message);
// The same bytes as encode_frame(WriteChannelMsg{channel_id, offset, data})
// for `data_bytes` of data, which `write_data` writes straight into the frame:
// a channel chunk is written once, not encoded into a vector, copied into the
// builder and copied again behind the size prefix.
EncodedFrame encode_write_channel_frame(uint32_t channel_id, uint64_t offset, size_t data_bytes,
                                        const std::function<void(std::span<uint8_t>)>& write_data);
Result<Message> decode_message(std::span<const uint8_t> body);
// The same, but a WriteChannel's data is read where it lies in `body`
// (WriteChannelMsg::in_frame), not copied out: for a reader that handles each
// message before it lets go of the frame, as the result stream's client does.
Result<Message> decode_message_in_frame(std::span<const uint8_t> body);

// A stable hash of lightcuts.fbs (first 16 hex digits of its SHA-256, computed
// at configure time); dumps carry it so a stale dump fails loudly.
uint64_t schema_hash();

}  // namespace lc

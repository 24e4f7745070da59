#pragma once
// Encodes our Message types to FlatBuffers Envelopes and back. Decoding runs the
// FlatBuffers Verifier (with depth/table limits and the frame's own size) and
// then checks enum ranges and required fields; nothing is read before that.
#include <cstdint>
#include <span>
#include <vector>

#include "messages.h"
#include "lightcuts/result.h"

namespace lc {

// The FlatBuffers body of a frame (no size prefix); file identifier "LCP1".
std::vector<uint8_t> encode_message(const Message& message);
// The full frame: size prefix + body.
std::vector<uint8_t> encode_frame(const Message& message);
Result<Message> decode_message(std::span<const uint8_t> body);

// A stable hash of lightcuts.fbs (first 16 hex digits of its SHA-256, computed
// at configure time); dumps carry it so a stale dump fails loudly.
uint64_t schema_hash();

}  // namespace lc

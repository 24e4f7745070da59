// The one translation unit that sees the FlatBuffers-generated message code
// (channel_records.cpp uses only its fixed-layout record structs). Decoding
// checks, in order: size, alignment, file identifier, the Verifier, the union
// type, trailing bytes, then every field's value; nothing is read before the
// Verifier has accepted the buffer.
#include "codec.h"

#include <cmath>
#include <cstring>
#include <memory>
#include <string>
#include <type_traits>

#include "frame_decoder.h"
#include "lightcuts_generated.h"
#include "schema_hash.h"

namespace lc {
namespace {

// Verifier limits: our messages nest three tables deep; the table cap bounds
// the work a hostile frame can ask for.
constexpr flatbuffers::uoffset_t kMaxVerifierDepth = 64;
constexpr flatbuffers::uoffset_t kMaxVerifierTables = 1000000;
// FlatBuffers reads scalars in place, so the body must sit at an address
// aligned like its largest scalar (ulong/double).
constexpr size_t kBodyAlignment = 8;
constexpr size_t kEnvelopeHeaderBytes = 8;  // root offset + file identifier

Error malformed(const std::string& what) { return make_error("malformed frame: " + what); }

fb::Guid to_fb(const Guid& g) { return fb::Guid(g.a, g.b, g.c, g.d); }
Guid from_fb(const fb::Guid& g) { return Guid{g.a(), g.b(), g.c(), g.d()}; }

std::string to_string(const flatbuffers::String* s) { return s ? s->str() : std::string(); }

// ---- encoding --------------------------------------------------------------

using Fbb = flatbuffers::FlatBufferBuilder;
using Body = std::pair<fb::Message, flatbuffers::Offset<void>>;

Body encode_body(Fbb& fbb, const HelloMsg& m) {
    const fb::Guid version = to_fb(m.protocol_version);
    auto peer = fbb.CreateString(m.peer_name);
    auto token = fbb.CreateString(m.token);
    return {fb::Message::Hello, fb::CreateHello(fbb, &version, peer, token).Union()};
}

Body encode_body(Fbb& fbb, const HelloAckMsg& m) {
    const fb::Guid version = to_fb(m.protocol_version);
    auto peer = fbb.CreateString(m.peer_name);
    return {fb::Message::HelloAck, fb::CreateHelloAck(fbb, &version, peer).Union()};
}

Body encode_body(Fbb& fbb, const OpenChannelMsg& m) {
    auto name = fbb.CreateString(m.name);
    return {fb::Message::OpenChannel,
            fb::CreateOpenChannel(fbb, m.channel_id, name, m.total_bytes).Union()};
}

Body encode_body(Fbb& fbb, const WriteChannelMsg& m) {
    const std::span<const uint8_t> bytes = m.bytes();
    auto data = fbb.CreateVector(bytes.data(), bytes.size());
    return {fb::Message::WriteChannel,
            fb::CreateWriteChannel(fbb, m.channel_id, m.offset, data).Union()};
}

Body encode_body(Fbb& fbb, const CloseChannelMsg& m) {
    return {fb::Message::CloseChannel, fb::CreateCloseChannel(fbb, m.channel_id).Union()};
}

Body encode_body(Fbb& fbb, const BakeRequestMsg& m) {
    auto scene = fbb.CreateString(m.scene_channel);
    // No environment: the field stays absent, as before it existed.
    flatbuffers::Offset<flatbuffers::String> environment;
    if (!m.environment_channel.empty()) environment = fbb.CreateString(m.environment_channel);
    // Left out when empty, so a bake without geometry sends today's bytes.
    flatbuffers::Offset<flatbuffers::String> geometry;
    if (!m.geometry_channel.empty()) geometry = fbb.CreateString(m.geometry_channel);
    auto table =
        fb::CreateBakeRequest(fbb, m.bake_id, scene, static_cast<fb::BuilderKind>(m.builder),
                              m.seed, static_cast<fb::RepresentativeRule>(m.representative_rule),
                              static_cast<fb::PairingMode>(m.pairing), m.exact_pairing_limit,
                              environment, m.environment_lights, geometry, m.area_lights,
                              static_cast<fb::IndirectMethod>(m.indirect.method), m.indirect.bounces,
                              m.indirect.vpl_count, m.indirect.patch_size, m.indirect.tolerance, m.ranks);
    return {fb::Message::BakeRequest, table.Union()};
}

Body encode_body(Fbb& fbb, const ProgressMsg& m) {
    auto stage = fbb.CreateString(m.stage);
    return {fb::Message::Progress, fb::CreateProgress(fbb, m.bake_id, stage, m.percent).Union()};
}

Body encode_body(Fbb& fbb, const WarningMsg& m) {
    auto text = fbb.CreateString(m.text);
    return {fb::Message::Warning, fb::CreateWarning(fbb, m.bake_id, text).Union()};
}

Body encode_body(Fbb& fbb, const ErrorMsg& m) {
    auto text = fbb.CreateString(m.text);
    return {fb::Message::ErrorMessage,
            fb::CreateErrorMessage(fbb, m.bake_id, static_cast<uint32_t>(m.code), text).Union()};
}

Body encode_body(Fbb& fbb, const CancelMsg& m) {
    return {fb::Message::Cancel, fb::CreateCancel(fbb, m.bake_id).Union()};
}

Body encode_body(Fbb& fbb, const BakeDoneMsg& m) {
    auto channel = fbb.CreateString(m.result_channel);
    flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<flatbuffers::String>>> effects;
    if (!m.effects.empty()) effects = fbb.CreateVectorOfStrings(m.effects);
    const fb::TreeLightCounts lights(m.lights.punctual, m.lights.area_samples, m.lights.environment,
                                     m.lights.vpls, m.lights.patches);
    auto table = fb::CreateBakeDone(fbb, m.bake_id, channel, m.node_count, m.leaf_count, m.build_ms,
                                    m.pairing_cost, m.pairing_lower_bound, m.exact, effects, &lights);
    return {fb::Message::BakeDone, table.Union()};
}

Body encode_body(Fbb& fbb, const StatusRequestMsg& m) {
    return {fb::Message::StatusRequest, fb::CreateStatusRequest(fbb, m.request_id).Union()};
}

Body encode_body(Fbb& fbb, const StatusReplyMsg& m) {
    std::vector<flatbuffers::Offset<fb::BakeStatus>> bakes;
    for (const BakeStatusEntry& b : m.bakes) {
        auto state = fbb.CreateString(b.state);
        auto stage = fbb.CreateString(b.stage);
        bakes.push_back(fb::CreateBakeStatus(fbb, b.connection, b.bake_id, state, stage, b.percent, b.ranks));
    }
    auto bake_vector = fbb.CreateVector(bakes);
    auto version = fbb.CreateString(m.version);
    auto launcher = fbb.CreateString(m.mpi_launcher);
    auto table = fb::CreateStatusReply(fbb, m.request_id, version, m.uptime_seconds, bake_vector,
                                       m.memory_budget_bytes, m.memory_held_bytes, m.connections,
                                       m.max_connections, m.max_concurrent_bakes, m.max_bake_seconds, launcher,
                                       m.mpi_max_ranks);
    return {fb::Message::StatusReply, table.Union()};
}

// ---- decoding: extent of a verified buffer ---------------------------------

// The FlatBuffers builder writes back to front, so the end of a buffer is the
// end of the first object built, followed by at most 3 bytes of zero padding.
// Tracking the furthest byte of every object we read finds trailing garbage,
// which the Verifier ignores.
class ExtentTracker {
public:
    ExtentTracker(const uint8_t* buf, size_t size) : buf_(buf), size_(size) {}

    // A verified table: its vtable, and its inline object (size from the vtable).
    bool table(const void* table) {
        const size_t start = offset_of(table);
        const auto* p = static_cast<const uint8_t*>(table);
        const auto vtable_distance = flatbuffers::ReadScalar<flatbuffers::soffset_t>(p);
        // The Verifier already proved the vtable lies inside the buffer.
        const size_t vtable = static_cast<size_t>(static_cast<int64_t>(start) - vtable_distance);
        const auto vtable_size = flatbuffers::ReadScalar<flatbuffers::voffset_t>(buf_ + vtable);
        size_t object_size = sizeof(flatbuffers::soffset_t);
        if (vtable_size >= 2 * sizeof(flatbuffers::voffset_t)) {
            object_size = flatbuffers::ReadScalar<flatbuffers::voffset_t>(
                buf_ + vtable + sizeof(flatbuffers::voffset_t));
        }
        if (object_size > size_ - start) return false;
        extend(vtable + vtable_size);
        extend(start + object_size);
        return true;
    }
    void string(const flatbuffers::String* s) {
        if (s) extend(offset_of(s) + sizeof(flatbuffers::uoffset_t) + s->size() + 1);
    }
    void strings(const flatbuffers::Vector<flatbuffers::Offset<flatbuffers::String>>* v) {
        if (!v) return;
        extend(offset_of(v) + sizeof(flatbuffers::uoffset_t) * (1 + v->size()));
        for (const flatbuffers::String* s : *v) string(s);
    }
    void vector(const flatbuffers::Vector<uint8_t>* v) {
        if (v) extend(offset_of(v) + sizeof(flatbuffers::uoffset_t) + v->size());
    }
    void extend(size_t end) { end_ = std::max(end_, end); }
    size_t end() const { return end_; }
    const uint8_t* base() const { return buf_; }

private:
    size_t offset_of(const void* p) const {
        return static_cast<size_t>(static_cast<const uint8_t*>(p) - buf_);
    }
    const uint8_t* buf_;
    size_t size_;
    size_t end_ = kEnvelopeHeaderBytes;
};

// ---- decoding: field checks -------------------------------------------------

template <typename Enum>
bool enum_in_range(Enum value) {
    using U = std::underlying_type_t<Enum>;
    return static_cast<U>(value) >= static_cast<U>(Enum::MIN) &&
           static_cast<U>(value) <= static_cast<U>(Enum::MAX);
}

Error bad_enum(const char* field, unsigned value) {
    return malformed(std::string(field) + " has unknown value " + std::to_string(value));
}

Error not_finite(const char* field, double value) {
    return malformed(std::string(field) + " is not finite (" + std::to_string(value) + ")");
}

Error missing(const char* field) { return malformed(std::string(field) + " is missing"); }

Result<Message> decode_table(const fb::Hello& t, ExtentTracker& extent) {
    extent.string(t.peer_name());
    extent.string(t.token());
    if (!t.protocol_version()) return missing("Hello.protocol_version");
    return Message{
        HelloMsg{from_fb(*t.protocol_version()), to_string(t.peer_name()), to_string(t.token())}};
}

Result<Message> decode_table(const fb::HelloAck& t, ExtentTracker& extent) {
    extent.string(t.peer_name());
    if (!t.protocol_version()) return missing("HelloAck.protocol_version");
    return Message{HelloAckMsg{from_fb(*t.protocol_version()), to_string(t.peer_name())}};
}

Result<Message> decode_table(const fb::OpenChannel& t, ExtentTracker& extent) {
    extent.string(t.name());
    if (!t.name()) return missing("OpenChannel.name");
    return Message{OpenChannelMsg{t.channel_id(), t.name()->str(), t.total_bytes()}};
}

Result<Message> decode_table(const fb::WriteChannel& t, ExtentTracker& extent) {
    extent.vector(t.data());
    WriteChannelMsg m{t.channel_id(), t.offset(), {}, {}};
    // A view for now: decode_body copies it out unless its caller keeps the frame.
    if (t.data()) m.in_frame = {t.data()->data(), t.data()->size()};
    return Message{std::move(m)};
}

Result<Message> decode_table(const fb::CloseChannel& t, ExtentTracker&) {
    return Message{CloseChannelMsg{t.channel_id()}};
}

Result<Message> decode_table(const fb::BakeRequest& t, ExtentTracker& extent) {
    extent.string(t.scene_channel());
    extent.string(t.environment_channel());
    extent.string(t.geometry_channel());
    if (!t.scene_channel()) return missing("BakeRequest.scene_channel");
    if (!enum_in_range(t.builder())) {
        return bad_enum("BakeRequest.builder", static_cast<unsigned>(t.builder()));
    }
    if (!enum_in_range(t.representative_rule())) {
        return bad_enum("BakeRequest.representative_rule",
                        static_cast<unsigned>(t.representative_rule()));
    }
    if (!enum_in_range(t.pairing())) {
        return bad_enum("BakeRequest.pairing", static_cast<unsigned>(t.pairing()));
    }
    if (!enum_in_range(t.indirect())) {
        return bad_enum("BakeRequest.indirect", static_cast<unsigned>(t.indirect()));
    }
    if (!std::isfinite(t.patch_size())) return not_finite("BakeRequest.patch_size", t.patch_size());
    if (!std::isfinite(t.radiosity_tolerance())) {
        return not_finite("BakeRequest.radiosity_tolerance", t.radiosity_tolerance());
    }
    BakeRequestMsg m;
    m.bake_id = t.bake_id();
    m.scene_channel = t.scene_channel()->str();
    m.builder = static_cast<BuilderKind>(t.builder());
    m.seed = t.seed();
    m.representative_rule = static_cast<RepresentativeRule>(t.representative_rule());
    m.pairing = static_cast<PairingMode>(t.pairing());
    m.exact_pairing_limit = t.exact_pairing_limit();
    m.environment_channel = to_string(t.environment_channel());
    m.environment_lights = t.environment_lights();
    m.geometry_channel = to_string(t.geometry_channel());
    m.area_lights = t.area_lights();
    m.indirect.method = static_cast<IndirectMethod>(t.indirect());
    m.indirect.bounces = t.indirect_bounces();
    m.indirect.vpl_count = t.vpl_count();
    m.indirect.patch_size = t.patch_size();
    m.indirect.tolerance = t.radiosity_tolerance();
    m.ranks = t.ranks();
    return Message{std::move(m)};
}

Result<Message> decode_table(const fb::Progress& t, ExtentTracker& extent) {
    extent.string(t.stage());
    if (!std::isfinite(t.percent())) return not_finite("Progress.percent", t.percent());
    return Message{ProgressMsg{t.bake_id(), to_string(t.stage()), t.percent()}};
}

Result<Message> decode_table(const fb::Warning& t, ExtentTracker& extent) {
    extent.string(t.text());
    return Message{WarningMsg{t.bake_id(), to_string(t.text())}};
}

Result<Message> decode_table(const fb::ErrorMessage& t, ExtentTracker& extent) {
    extent.string(t.text());
    // A newer peer may send codes we do not know; they still are errors.
    const uint32_t code = t.code();
    const ErrorCode known = code <= static_cast<uint32_t>(ErrorCode::kBusy)
                                ? static_cast<ErrorCode>(code)
                                : ErrorCode::kUnknown;
    return Message{ErrorMsg{t.bake_id(), known, to_string(t.text())}};
}

Result<Message> decode_table(const fb::Cancel& t, ExtentTracker&) {
    return Message{CancelMsg{t.bake_id()}};
}

Result<Message> decode_table(const fb::BakeDone& t, ExtentTracker& extent) {
    extent.string(t.result_channel());
    extent.strings(t.effects());
    if (!std::isfinite(t.build_ms())) return not_finite("BakeDone.build_ms", t.build_ms());
    if (!std::isfinite(t.pairing_cost())) {
        return not_finite("BakeDone.pairing_cost", t.pairing_cost());
    }
    if (!std::isfinite(t.pairing_lower_bound())) {
        return not_finite("BakeDone.pairing_lower_bound", t.pairing_lower_bound());
    }
    BakeDoneMsg m;
    m.bake_id = t.bake_id();
    m.result_channel = to_string(t.result_channel());
    m.node_count = t.node_count();
    m.leaf_count = t.leaf_count();
    m.build_ms = t.build_ms();
    m.pairing_cost = t.pairing_cost();
    m.pairing_lower_bound = t.pairing_lower_bound();
    m.exact = t.exact();
    if (t.effects())
        for (const flatbuffers::String* line : *t.effects()) m.effects.push_back(line->str());
    if (const fb::TreeLightCounts* lights = t.lights())
        m.lights = {lights->punctual(), lights->area_samples(), lights->environment(), lights->vpls(),
                    lights->patches()};
    return Message{std::move(m)};
}

Result<Message> decode_table(const fb::StatusRequest& t, ExtentTracker&) {
    return Message{StatusRequestMsg{t.request_id()}};
}

Result<Message> decode_table(const fb::StatusReply& t, ExtentTracker& extent) {
    extent.string(t.version());
    extent.string(t.mpi_launcher());
    if (!std::isfinite(t.uptime_seconds())) return not_finite("StatusReply.uptime_seconds", t.uptime_seconds());
    StatusReplyMsg m;
    m.request_id = t.request_id();
    m.version = to_string(t.version());
    m.uptime_seconds = t.uptime_seconds();
    if (const auto* bakes = t.bakes()) {
        extent.extend(size_t(reinterpret_cast<const uint8_t*>(bakes) - extent.base()) +
                      sizeof(flatbuffers::uoffset_t) * (1 + bakes->size()));
        for (const fb::BakeStatus* b : *bakes) {
            if (!extent.table(b)) return malformed("StatusReply.bakes entry extends past the end of the frame");
            extent.string(b->state());
            extent.string(b->stage());
            if (!std::isfinite(b->percent())) return not_finite("StatusReply.bakes.percent", b->percent());
            m.bakes.push_back({b->connection(), b->bake_id(), to_string(b->state()), to_string(b->stage()),
                               b->percent(), b->ranks()});
        }
    }
    m.memory_budget_bytes = t.memory_budget_bytes();
    m.memory_held_bytes = t.memory_held_bytes();
    m.connections = t.connections();
    m.max_connections = t.max_connections();
    m.max_concurrent_bakes = t.max_concurrent_bakes();
    m.max_bake_seconds = t.max_bake_seconds();
    m.mpi_launcher = to_string(t.mpi_launcher());
    m.mpi_max_ranks = t.mpi_max_ranks();
    return Message{std::move(m)};
}

bool all_zero(const uint8_t* p, size_t n) {
    for (size_t i = 0; i < n; ++i) {
        if (p[i] != 0) return false;
    }
    return true;
}

template <typename Table>
Result<Message> decode_union(const uint8_t* buf, size_t body_size, const fb::Envelope& envelope,
                             const char* name, ExtentTracker& extent) {
    const Table* table = envelope.message_as<Table>();
    if (!table) return missing((std::string("Envelope.message (") + name + ")").c_str());
    if (!extent.table(table)) {
        return malformed(std::string(name) + " table extends past the end of the frame");
    }
    Result<Message> message = decode_table(*table, extent);
    if (!message) return message;
    // Only the builder's alignment padding (< 4 zero bytes) may follow the data.
    const size_t end = extent.end();
    if (end > body_size) {
        return malformed(std::string(name) + " extends past the end of the frame");
    }
    if (body_size - end >= sizeof(flatbuffers::uoffset_t) ||
        !all_zero(buf + end, body_size - end)) {
        return malformed(std::string(name) + " frame has " + std::to_string(body_size - end) +
                         " trailing bytes after its data");
    }
    return message;
}

Result<Message> decode_verified(const uint8_t* buf, size_t size) {
    const fb::Envelope* envelope = fb::GetEnvelope(buf);
    ExtentTracker extent(buf, size);
    if (!extent.table(envelope)) return malformed("Envelope extends past the end of the frame");

    const auto type = envelope->message_type();
    switch (type) {
        case fb::Message::NONE: return malformed("Envelope.message is empty (union type NONE)");
        case fb::Message::Hello:
            return decode_union<fb::Hello>(buf, size, *envelope, "Hello", extent);
        case fb::Message::HelloAck:
            return decode_union<fb::HelloAck>(buf, size, *envelope, "HelloAck", extent);
        case fb::Message::OpenChannel:
            return decode_union<fb::OpenChannel>(buf, size, *envelope, "OpenChannel", extent);
        case fb::Message::WriteChannel:
            return decode_union<fb::WriteChannel>(buf, size, *envelope, "WriteChannel", extent);
        case fb::Message::CloseChannel:
            return decode_union<fb::CloseChannel>(buf, size, *envelope, "CloseChannel", extent);
        case fb::Message::BakeRequest:
            return decode_union<fb::BakeRequest>(buf, size, *envelope, "BakeRequest", extent);
        case fb::Message::Progress:
            return decode_union<fb::Progress>(buf, size, *envelope, "Progress", extent);
        case fb::Message::Warning:
            return decode_union<fb::Warning>(buf, size, *envelope, "Warning", extent);
        case fb::Message::ErrorMessage:
            return decode_union<fb::ErrorMessage>(buf, size, *envelope, "ErrorMessage", extent);
        case fb::Message::Cancel:
            return decode_union<fb::Cancel>(buf, size, *envelope, "Cancel", extent);
        case fb::Message::BakeDone:
            return decode_union<fb::BakeDone>(buf, size, *envelope, "BakeDone", extent);
        case fb::Message::StatusRequest:
            return decode_union<fb::StatusRequest>(buf, size, *envelope, "StatusRequest", extent);
        case fb::Message::StatusReply:
            return decode_union<fb::StatusReply>(buf, size, *envelope, "StatusReply", extent);
    }
    return malformed("Envelope.message has unknown union type " +
                     std::to_string(static_cast<unsigned>(type)));
}

std::string printable_identifier(const uint8_t* p) {
    std::string text;
    for (int i = 0; i < 4; ++i) {
        const char c = static_cast<char>(p[i]);
        if (c >= 0x20 && c < 0x7F) {
            text += c;
        } else {
            static const char* kHex = "0123456789ABCDEF";
            text += "\\x";
            text += kHex[p[i] >> 4];
            text += kHex[p[i] & 0xF];
        }
    }
    return text;
}

// Builds the Envelope into `fbb`; the span points into the builder.
std::span<const uint8_t> build_envelope(Fbb& fbb, const Message& message) {
    const Body body = std::visit([&fbb](const auto& m) { return encode_body(fbb, m); }, message);
    fb::FinishEnvelopeBuffer(fbb, fb::CreateEnvelope(fbb, body.first, body.second));
    return {fbb.GetBufferPointer(), fbb.GetSize()};
}

// Builder room beyond a message's channel data: more than any envelope's
// tables, so a channel chunk never makes the builder regrow.
constexpr size_t kEnvelopeRoomBytes = 256;

size_t initial_builder_bytes(const Message& message) {
    size_t initial = kEnvelopeRoomBytes;
    if (const auto* write = std::get_if<WriteChannelMsg>(&message)) initial += write->bytes().size();
    return initial;
}

// Takes the finished envelope out of `fbb`, the size prefix in front of it.
EncodedFrame take_frame(Fbb& fbb) {
    const size_t body_size = fbb.GetSize();
    size_t reserved = 0;
    size_t offset = 0;
    // The builder's default allocator made its buffer with new[].
    std::unique_ptr<uint8_t[]> storage(fbb.ReleaseRaw(reserved, offset));
    if (offset < kFrameHeaderBytes) {
        // The builder grew to fit the body exactly: no room in front, copy once.
        auto framed = std::make_unique_for_overwrite<uint8_t[]>(kFrameHeaderBytes + body_size);
        std::memcpy(framed.get() + kFrameHeaderBytes, storage.get() + offset, body_size);
        storage = std::move(framed);
        offset = kFrameHeaderBytes;
    }
    put_frame_header(body_size, storage.get() + offset - kFrameHeaderBytes);
    return EncodedFrame(std::move(storage), offset - kFrameHeaderBytes, kFrameHeaderBytes + body_size);
}

}  // namespace

std::vector<uint8_t> encode_message(const Message& message) {
    Fbb fbb(initial_builder_bytes(message));
    const std::span<const uint8_t> body = build_envelope(fbb, message);
    return std::vector<uint8_t>(body.begin(), body.end());
}

std::vector<uint8_t> encode_frame(const Message& message) {
    // Framed straight from the builder: one copy of a chunk, not two.
    Fbb fbb(initial_builder_bytes(message));
    return frame_bytes(build_envelope(fbb, message));
}

EncodedFrame encode_frame_in_place(const Message& message) {
    Fbb fbb(initial_builder_bytes(message));
    build_envelope(fbb, message);
    return take_frame(fbb);
}

EncodedFrame encode_write_channel_frame(uint32_t channel_id, uint64_t offset, size_t data_bytes,
                                        const std::function<void(std::span<uint8_t>)>& write_data) {
    Fbb fbb(kEnvelopeRoomBytes + data_bytes);
    // Laid out as CreateVector lays out a copy of the data (encode_body), so
    // the frame's bytes are encode_frame's.
    uint8_t* data = nullptr;
    const auto vector = fbb.CreateUninitializedVector<uint8_t>(data_bytes, &data);
    // Written now: the pointer is good until the builder next grows.
    write_data({data, data_bytes});
    const auto table = fb::CreateWriteChannel(fbb, channel_id, offset, vector);
    fb::FinishEnvelopeBuffer(fbb, fb::CreateEnvelope(fbb, fb::Message::WriteChannel, table.Union()));
    return take_frame(fbb);
}

namespace {

// Moves a WriteChannel's data out of the frame into the message.
void copy_channel_data_out(Message& message) {
    if (auto* write = std::get_if<WriteChannelMsg>(&message); write && !write->in_frame.empty()) {
        write->data.assign(write->in_frame.begin(), write->in_frame.end());
        write->in_frame = {};
    }
}

Result<Message> decode_body(std::span<const uint8_t> body, bool channel_data_in_frame) {
    if (body.size() < kEnvelopeHeaderBytes + sizeof(flatbuffers::uoffset_t)) {
        return malformed("frame of " + std::to_string(body.size()) +
                         " bytes is too short for an Envelope");
    }
    // The builder always pads a finished buffer to at least 4-byte alignment.
    if (body.size() % sizeof(flatbuffers::uoffset_t) != 0) {
        return malformed("Envelope size " + std::to_string(body.size()) +
                         " is not a multiple of 4");
    }
    if (body.size() >= FLATBUFFERS_MAX_BUFFER_SIZE) {
        return malformed("frame of " + std::to_string(body.size()) +
                         " bytes exceeds the FlatBuffers limit");
    }
    // Misaligned input (e.g. a frame cut out of a larger buffer) is copied so
    // that in-place scalar reads stay aligned.
    std::unique_ptr<uint64_t[]> aligned_copy;
    const uint8_t* buf = body.data();
    if (reinterpret_cast<uintptr_t>(buf) % kBodyAlignment != 0) {
        aligned_copy = std::make_unique<uint64_t[]>((body.size() + 7) / 8);
        std::memcpy(aligned_copy.get(), body.data(), body.size());
        buf = reinterpret_cast<const uint8_t*>(aligned_copy.get());
    }
    if (!fb::EnvelopeBufferHasIdentifier(buf)) {
        return malformed("file identifier is '" +
                         printable_identifier(buf + sizeof(flatbuffers::uoffset_t)) +
                         "', expected '" + fb::EnvelopeIdentifier() + "'");
    }
    flatbuffers::Verifier::Options options;
    options.max_depth = kMaxVerifierDepth;
    options.max_tables = kMaxVerifierTables;
    options.check_alignment = true;
    flatbuffers::Verifier verifier(buf, body.size(), options);
    if (!fb::VerifyEnvelopeBuffer(verifier)) {
        return malformed("Envelope of " + std::to_string(body.size()) +
                         " bytes failed FlatBuffers verification");
    }
    Result<Message> message = decode_verified(buf, body.size());
    // A view into the aligned copy would outlive it.
    if (message && (!channel_data_in_frame || aligned_copy)) copy_channel_data_out(*message);
    return message;
}

}  // namespace

Result<Message> decode_message(std::span<const uint8_t> body) {
    return decode_body(body, false);
}

Result<Message> decode_message_in_frame(std::span<const uint8_t> body) {
    return decode_body(body, true);
}

uint64_t schema_hash() { return detail::kSchemaHash; }

}  // namespace lc

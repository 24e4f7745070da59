// codec: every message round-trips; hostile frames (truncated, bit-flipped,
// over-long, wrong identifier, unknown union type, bad enums) fail cleanly.
#include "protocol/codec.h"

#include <gtest/gtest.h>
#include <openssl/sha.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <tuple>
#include <vector>

#include "protocol/frame_decoder.h"
#include "test_paths.h"

namespace lc {
namespace {

// ---- field-by-field equality (the message structs carry no operator==) ----

bool same(const HelloMsg& x, const HelloMsg& y) {
    return x.protocol_version == y.protocol_version && x.peer_name == y.peer_name &&
           x.token == y.token;
}
bool same(const HelloAckMsg& x, const HelloAckMsg& y) {
    return x.protocol_version == y.protocol_version && x.peer_name == y.peer_name;
}
bool same(const OpenChannelMsg& x, const OpenChannelMsg& y) {
    return x.channel_id == y.channel_id && x.name == y.name && x.total_bytes == y.total_bytes;
}
bool same(const WriteChannelMsg& x, const WriteChannelMsg& y) {
    return x.channel_id == y.channel_id && x.offset == y.offset && x.data == y.data;
}
bool same(const CloseChannelMsg& x, const CloseChannelMsg& y) {
    return x.channel_id == y.channel_id;
}
bool same(const BakeRequestMsg& x, const BakeRequestMsg& y) {
    return x.bake_id == y.bake_id && x.scene_channel == y.scene_channel && x.builder == y.builder &&
           x.seed == y.seed && x.representative_rule == y.representative_rule &&
           x.pairing == y.pairing && x.exact_pairing_limit == y.exact_pairing_limit &&
           x.geometry_channel == y.geometry_channel && x.area_lights == y.area_lights &&
           x.indirect.method == y.indirect.method && x.indirect.bounces == y.indirect.bounces &&
           x.indirect.vpl_count == y.indirect.vpl_count && x.indirect.patch_size == y.indirect.patch_size &&
           x.indirect.tolerance == y.indirect.tolerance;
}
bool same(const ProgressMsg& x, const ProgressMsg& y) {
    return x.bake_id == y.bake_id && x.stage == y.stage && x.percent == y.percent;
}
bool same(const WarningMsg& x, const WarningMsg& y) {
    return x.bake_id == y.bake_id && x.text == y.text;
}
bool same(const ErrorMsg& x, const ErrorMsg& y) {
    return x.bake_id == y.bake_id && x.code == y.code && x.text == y.text;
}
bool same(const CancelMsg& x, const CancelMsg& y) { return x.bake_id == y.bake_id; }
bool same(const BakeDoneMsg& x, const BakeDoneMsg& y) {
    return x.bake_id == y.bake_id && x.result_channel == y.result_channel &&
           x.node_count == y.node_count && x.leaf_count == y.leaf_count &&
           x.build_ms == y.build_ms && x.pairing_cost == y.pairing_cost &&
           x.pairing_lower_bound == y.pairing_lower_bound && x.exact == y.exact &&
           x.effects == y.effects && x.lights == y.lights;
}
bool same(const StatusRequestMsg& x, const StatusRequestMsg& y) { return x.request_id == y.request_id; }
bool same(const StatusReplyMsg& x, const StatusReplyMsg& y) {
    auto entry = [](const BakeStatusEntry& b) {
        return std::tie(b.connection, b.bake_id, b.state, b.stage, b.percent, b.ranks);
    };
    if (x.bakes.size() != y.bakes.size()) return false;
    for (size_t i = 0; i < x.bakes.size(); ++i)
        if (entry(x.bakes[i]) != entry(y.bakes[i])) return false;
    return std::tie(x.request_id, x.version, x.uptime_seconds, x.memory_budget_bytes, x.memory_held_bytes,
                    x.connections, x.max_connections, x.max_concurrent_bakes, x.max_bake_seconds, x.mpi_launcher,
                    x.mpi_max_ranks) == std::tie(y.request_id, y.version, y.uptime_seconds, y.memory_budget_bytes,
                                                 y.memory_held_bytes, y.connections, y.max_connections,
                                                 y.max_concurrent_bakes, y.max_bake_seconds, y.mpi_launcher,
                                                 y.mpi_max_ranks);
}
bool same(const Message& x, const Message& y) {
    if (x.index() != y.index()) return false;
    return std::visit(
        [&y](const auto& mx) {
            using T = std::decay_t<decltype(mx)>;
            return same(mx, std::get<T>(y));
        },
        x);
}

StatusReplyMsg status_reply() {
    StatusReplyMsg m{9, "lightmass_server 0.1.0", 12.5, {}, 4ull << 30, 123456789, 3, 256, 2, 600, "mpirun", 16};
    m.bakes = {{5, 42, "running", "pairing level 3", 37.5f, 0}, {6, 43, "queued", "", 0.0f, 4}};
    return m;
}

// One message of every kind, with no field left at its default.
std::vector<Message> sample_messages() {
    std::vector<uint8_t> data(1000);
    for (size_t i = 0; i < data.size(); ++i) data[i] = static_cast<uint8_t>(i * 7 + 3);
    BakeRequestMsg bake{42,
                        "4C435363656E65466F726D6174000001.0123.scene",
                        BuilderKind::kAgglomerative,
                        0xFEEDFACECAFEBEEFull,
                        RepresentativeRule::kThesisFirst,
                        PairingMode::kApproximate,
                        4096,
                        "4C435363656E65466F726D6174000001.0123.geom",
                        777};
    bake.indirect = {IndirectMethod::kRadiosity, 3, 123456789012ull, 0.125f, 0.002f};
    BakeDoneMsg done{42, "result", 9, 5, 12.5, 1234.25, 1200.0, false,
                     {"area lights: simulated (2 emissive triangles, 777 samples)", "second"},
                     {8, 777, 203, 1054763, 5000000000ull}};
    return {
        HelloMsg{kProtocolVersion, "editor_client 0.1", "s3cret-token"},
        HelloAckMsg{kProtocolVersion, "lightmass_server 0.1"},
        OpenChannelMsg{7, "4C69676874637574735665727369666E.4C696768746375747344617461475549.lcut",
                       1u << 20},
        WriteChannelMsg{7, 123456789012ull, data},
        CloseChannelMsg{7},
        bake,
        ProgressMsg{42, "pairing level 3", 37.5f},
        WarningMsg{42, "approximate pairing above 8192 nodes"},
        ErrorMsg{42, ErrorCode::kVersionMismatch, "peer speaks version X, we speak Y"},
        CancelMsg{42},
        done,
        StatusRequestMsg{9},
        status_reply(),
    };
}

// The same kinds with every field at its zero/empty value.
std::vector<Message> default_messages() {
    return {HelloMsg{},        HelloAckMsg{},    OpenChannelMsg{}, WriteChannelMsg{},
            CloseChannelMsg{}, BakeRequestMsg{}, ProgressMsg{},    WarningMsg{},
            ErrorMsg{},        CancelMsg{},      BakeDoneMsg{},    StatusRequestMsg{},
            StatusReplyMsg{}};
}

TEST(Codec, EveryMessageRoundTrips) {
    for (const auto& set : {sample_messages(), default_messages()}) {
        ASSERT_EQ(set.size(), std::variant_size_v<Message>);
        for (const Message& m : set) {
            const auto body = encode_message(m);
            Result<Message> decoded = decode_message(body);
            ASSERT_TRUE(decoded.ok()) << message_name(m) << ": " << decoded.error();
            EXPECT_TRUE(same(m, *decoded)) << message_name(m);
        }
    }
}

TEST(Codec, BodyCarriesFileIdentifierAndFrameCarriesSize) {
    for (const Message& m : sample_messages()) {
        const auto body = encode_message(m);
        ASSERT_GE(body.size(), 8u);
        EXPECT_EQ(std::string(body.begin() + 4, body.begin() + 8), "LCP1");
        EXPECT_EQ(body.size() % 4, 0u);
        EXPECT_EQ(encode_frame(m), frame_bytes(body));
        EXPECT_EQ(encode_message(m), body) << "encoding must be deterministic";
    }
}

TEST(Codec, FramesBuiltInPlaceAreTheSameBytes) {
    BakeDoneMsg many_effects;
    // Past the builder's first buffer, so it regrows before the frame is taken.
    many_effects.effects.assign(64, std::string(100, 'e'));
    std::vector<Message> messages = sample_messages();
    for (const Message& m : default_messages()) messages.push_back(m);
    messages.push_back(many_effects);
    for (const Message& m : messages) {
        const std::vector<uint8_t> expected = encode_frame(m);
        const EncodedFrame frame = encode_frame_in_place(m);
        EXPECT_TRUE(std::ranges::equal(frame.bytes(), expected)) << message_name(m);
    }
}

TEST(Codec, WriteChannelFrameWrittenInPlaceIsTheSameBytes) {
    for (size_t size : {size_t{0}, size_t{1}, size_t{3}, size_t{180}, size_t{1} << 20}) {
        WriteChannelMsg write{9, 1234567, std::vector<uint8_t>(size)};
        for (size_t i = 0; i < size; ++i) write.data[i] = static_cast<uint8_t>(i * 7 + 1);
        const EncodedFrame frame =
            encode_write_channel_frame(write.channel_id, write.offset, size, [&](std::span<uint8_t> data) {
                ASSERT_EQ(data.size(), size);
                std::copy(write.data.begin(), write.data.end(), data.begin());
            });
        EXPECT_TRUE(std::ranges::equal(frame.bytes(), encode_frame(write))) << size << " bytes";
    }
}

TEST(Codec, WriteChannelDataIsCopiedOut) {
    WriteChannelMsg write{1, 0, std::vector<uint8_t>(1u << 20)};
    for (size_t i = 0; i < write.data.size(); ++i)
        write.data[i] = static_cast<uint8_t>(i ^ (i >> 8));
    auto body = encode_message(write);
    Result<Message> decoded = decode_message(body);
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    std::fill(body.begin(), body.end(), 0xAB);
    body.clear();
    body.shrink_to_fit();
    EXPECT_EQ(std::get<WriteChannelMsg>(*decoded).data, write.data);
}

TEST(Codec, WriteChannelDecodedInFrameIsAViewOfTheFrame) {
    WriteChannelMsg write{3, 77, std::vector<uint8_t>(4096)};
    for (size_t i = 0; i < write.data.size(); ++i) write.data[i] = static_cast<uint8_t>(i * 13);
    const auto body = encode_message(write);
    Result<Message> decoded = decode_message_in_frame(body);
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    const auto& in_frame = std::get<WriteChannelMsg>(*decoded);
    EXPECT_TRUE(in_frame.data.empty());
    EXPECT_GE(in_frame.in_frame.data(), body.data());
    EXPECT_LE(in_frame.in_frame.data() + in_frame.in_frame.size(), body.data() + body.size());
    EXPECT_TRUE(std::ranges::equal(in_frame.bytes(), write.data));
    EXPECT_EQ(in_frame.channel_id, 3u);
    EXPECT_EQ(in_frame.offset, 77u);

    // A misaligned frame is read from an aligned copy, which goes: the data is copied out.
    std::vector<uint8_t> shifted(body.size() + 1);
    std::copy(body.begin(), body.end(), shifted.begin() + 1);
    Result<Message> copied = decode_message_in_frame(std::span(shifted).subspan(1));
    ASSERT_TRUE(copied.ok()) << copied.error();
    EXPECT_TRUE(std::get<WriteChannelMsg>(*copied).in_frame.empty());
    EXPECT_EQ(std::get<WriteChannelMsg>(*copied).data, write.data);
}

TEST(Codec, DecodesMisalignedInput) {
    for (const Message& m : sample_messages()) {
        const auto body = encode_message(m);
        std::vector<uint8_t> shifted(body.size() + 3);
        std::copy(body.begin(), body.end(), shifted.begin() + 3);
        Result<Message> decoded = decode_message(std::span(shifted).subspan(3));
        ASSERT_TRUE(decoded.ok()) << decoded.error();
        EXPECT_TRUE(same(m, *decoded));
    }
}

TEST(Codec, UnknownErrorCodesBecomeUnknown) {
    const auto body = encode_message(ErrorMsg{3, static_cast<ErrorCode>(99), "from the future"});
    Result<Message> decoded = decode_message(body);
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    EXPECT_EQ(std::get<ErrorMsg>(*decoded).code, ErrorCode::kUnknown);
    EXPECT_EQ(std::get<ErrorMsg>(*decoded).text, "from the future");
}

TEST(Codec, EveryTruncationIsRejected) {
    for (const Message& m : sample_messages()) {
        const auto body = encode_message(m);
        for (size_t length = 0; length < body.size(); ++length) {
            Result<Message> decoded = decode_message(std::span(body).first(length));
            ASSERT_FALSE(decoded.ok()) << message_name(m) << " cut to " << length << " of "
                                       << body.size() << " bytes was accepted";
            EXPECT_NE(decoded.error().find("malformed frame"), std::string::npos);
        }
    }
}

TEST(Codec, TrailingBytesAreRejected) {
    for (const Message& m : sample_messages()) {
        for (size_t extra : {1u, 3u, 4u, 8u, 100u}) {
            for (uint8_t fill : {uint8_t{0}, uint8_t{0x5A}}) {
                auto body = encode_message(m);
                body.insert(body.end(), extra, fill);
                Result<Message> decoded = decode_message(body);
                ASSERT_FALSE(decoded.ok()) << message_name(m) << " + " << extra << " bytes";
            }
        }
    }
    auto body = encode_message(CancelMsg{1});
    body.insert(body.end(), 8, 0x77);
    Result<Message> decoded = decode_message(body);
    ASSERT_FALSE(decoded.ok());
    EXPECT_NE(decoded.error().find("trailing"), std::string::npos) << decoded.error();
}

TEST(Codec, WrongIdentifierIsRejectedAndNamed) {
    auto body = encode_message(CancelMsg{1});
    body[7] = '2';
    Result<Message> decoded = decode_message(body);
    ASSERT_FALSE(decoded.ok());
    EXPECT_NE(decoded.error().find("'LCP2'"), std::string::npos) << decoded.error();
    EXPECT_NE(decoded.error().find("'LCP1'"), std::string::npos) << decoded.error();
}

TEST(Codec, TooShortFramesAreRejected) {
    const std::vector<uint8_t> zeros(16, 0);
    for (size_t length = 0; length <= zeros.size(); ++length) {
        EXPECT_FALSE(decode_message(std::span(zeros).first(length)).ok()) << length;
    }
}

// A hand-assembled Envelope whose union member is an empty table, to reach
// what our encoder never writes: a missing field or an unknown union type.
//   [0]  root offset -> 16        [4] "LCP1"
//   [8]  Envelope vtable: size 8, object 12, message_type at +8, message at +4
//   [16] Envelope: soffset 8, message offset -> 32, message_type, 3 bytes padding
//   [28] empty vtable: size 4, object 4      [32] empty table: soffset 4
std::vector<uint8_t> envelope_with_empty_table(uint8_t union_type) {
    std::vector<uint8_t> b(36, 0);
    auto u16 = [&b](size_t at, uint16_t v) {
        b[at] = static_cast<uint8_t>(v);
        b[at + 1] = static_cast<uint8_t>(v >> 8);
    };
    auto u32 = [&b](size_t at, uint32_t v) {
        for (int i = 0; i < 4; ++i) b[at + i] = static_cast<uint8_t>(v >> (8 * i));
    };
    u32(0, 16);
    b[4] = 'L', b[5] = 'C', b[6] = 'P', b[7] = '1';
    u16(8, 8), u16(10, 12), u16(12, 8), u16(14, 4);
    u32(16, 8);
    u32(20, 32 - 20);
    b[24] = union_type;
    u16(28, 4), u16(30, 4);
    u32(32, 4);
    return b;
}

TEST(Codec, HandAssembledEnvelopeDecodes) {
    // Sanity check of the helper: an empty Cancel table is a Cancel with bake_id 0.
    Result<Message> decoded = decode_message(envelope_with_empty_table(10));
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    EXPECT_EQ(std::get<CancelMsg>(*decoded).bake_id, 0u);
}

TEST(Codec, UnknownUnionTypeIsRejected) {
    // 13 message kinds (1..13): 14 is the first unknown one.
    for (uint8_t type : {uint8_t{14}, uint8_t{200}, uint8_t{255}}) {
        Result<Message> decoded = decode_message(envelope_with_empty_table(type));
        ASSERT_FALSE(decoded.ok()) << int(type);
        EXPECT_NE(decoded.error().find("unknown union type " + std::to_string(type)),
                  std::string::npos)
            << decoded.error();
    }
    Result<Message> none = decode_message(envelope_with_empty_table(0));
    ASSERT_FALSE(none.ok());
    EXPECT_NE(none.error().find("NONE"), std::string::npos) << none.error();
}

TEST(Codec, UnknownUnionTypeFoundByPatchingAnEncodedFrame) {
    // Cancel and CloseChannel share a layout, so their frames differ in the type byte only.
    const auto cancel = encode_message(CancelMsg{77});
    const auto close = encode_message(CloseChannelMsg{77});
    ASSERT_EQ(cancel.size(), close.size());
    std::vector<size_t> differing;
    for (size_t i = 0; i < cancel.size(); ++i) {
        if (cancel[i] != close[i]) differing.push_back(i);
    }
    ASSERT_EQ(differing.size(), 1u);
    auto patched = cancel;
    patched[differing[0]] = 14;
    Result<Message> decoded = decode_message(patched);
    ASSERT_FALSE(decoded.ok());
    EXPECT_NE(decoded.error().find("unknown union type 14"), std::string::npos) << decoded.error();
}

TEST(Codec, MissingRequiredFieldsAreNamed) {
    const std::vector<std::pair<uint8_t, std::string>> cases{
        {1, "Hello.protocol_version"},
        {2, "HelloAck.protocol_version"},
        {3, "OpenChannel.name"},
        {6, "BakeRequest.scene_channel"},
    };
    for (const auto& [type, field] : cases) {
        Result<Message> decoded = decode_message(envelope_with_empty_table(type));
        ASSERT_FALSE(decoded.ok()) << field;
        EXPECT_NE(decoded.error().find(field + " is missing"), std::string::npos)
            << decoded.error();
    }
}

TEST(Codec, OutOfRangeEnumsAreRejectedAndNamed) {
    BakeRequestMsg base{
        1, "scene", BuilderKind::kLbvh, 5, RepresentativeRule::kIntensity, PairingMode::kAuto, 0};
    BakeRequestMsg bad_builder = base;
    bad_builder.builder = static_cast<BuilderKind>(3);
    BakeRequestMsg bad_rule = base;
    bad_rule.representative_rule = static_cast<RepresentativeRule>(2);
    BakeRequestMsg bad_pairing = base;
    bad_pairing.pairing = static_cast<PairingMode>(250);
    BakeRequestMsg bad_indirect = base;
    bad_indirect.indirect.method = static_cast<IndirectMethod>(3);
    const std::vector<std::pair<BakeRequestMsg, std::string>> cases{
        {bad_builder, "BakeRequest.builder has unknown value 3"},
        {bad_rule, "BakeRequest.representative_rule has unknown value 2"},
        {bad_pairing, "BakeRequest.pairing has unknown value 250"},
        {bad_indirect, "BakeRequest.indirect has unknown value 3"},
    };
    for (const auto& [message, expected] : cases) {
        Result<Message> decoded = decode_message(encode_message(message));
        ASSERT_FALSE(decoded.ok()) << expected;
        EXPECT_NE(decoded.error().find(expected), std::string::npos) << decoded.error();
    }
    EXPECT_TRUE(decode_message(encode_message(base)).ok());
}

TEST(Codec, NonFiniteNumbersAreRejected) {
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    Result<Message> progress = decode_message(encode_message(ProgressMsg{1, "x", nan}));
    ASSERT_FALSE(progress.ok());
    EXPECT_NE(progress.error().find("Progress.percent"), std::string::npos) << progress.error();
    BakeDoneMsg done;
    done.build_ms = inf;
    Result<Message> bake_done = decode_message(encode_message(done));
    ASSERT_FALSE(bake_done.ok());
    EXPECT_NE(bake_done.error().find("BakeDone.build_ms"), std::string::npos);
    done.build_ms = 1.0;
    done.pairing_lower_bound = -inf;
    EXPECT_FALSE(decode_message(encode_message(done)).ok());
    BakeRequestMsg request{.scene_channel = "scene"};
    request.indirect.patch_size = nan;
    Result<Message> bad_patch = decode_message(encode_message(request));
    ASSERT_FALSE(bad_patch.ok());
    EXPECT_NE(bad_patch.error().find("BakeRequest.patch_size"), std::string::npos) << bad_patch.error();
}

// Every single-bit corruption of several frames either fails cleanly or yields
// a message that re-encodes and decodes to itself. Run under ASan/UBSan too.
TEST(Codec, BitFlipsFailCleanlyOrDecodeToValidMessages) {
    size_t accepted = 0;
    size_t rejected = 0;
    std::vector<Message> messages = sample_messages();
    // Keep WriteChannel small so the test stays fast.
    std::get<WriteChannelMsg>(messages[3]).data.resize(24);
    for (const Message& m : messages) {
        const auto body = encode_message(m);
        for (size_t bit = 0; bit < body.size() * 8; ++bit) {
            auto flipped = body;
            flipped[bit / 8] ^= static_cast<uint8_t>(1u << (bit % 8));
            Result<Message> decoded = decode_message(flipped);
            if (!decoded.ok()) {
                ++rejected;
                ASSERT_FALSE(decoded.error().empty());
                continue;
            }
            ++accepted;
            Result<Message> again = decode_message(encode_message(*decoded));
            ASSERT_TRUE(again.ok()) << again.error();
            ASSERT_TRUE(same(*decoded, *again)) << message_name(m) << " bit " << bit;
            if (const auto* p = std::get_if<ProgressMsg>(&decoded.value())) {
                ASSERT_TRUE(std::isfinite(p->percent));
            }
        }
    }
    std::printf("bit flips: %zu accepted as other valid messages, %zu rejected\n", accepted,
                rejected);
    EXPECT_GT(rejected, 0u);
}

TEST(Codec, RandomByteCorruptionFailsCleanlyOrDecodesToValidMessages) {
    std::mt19937 rng(2005);
    const std::vector<Message> messages = default_messages();
    for (int trial = 0; trial < 20000; ++trial) {
        auto body = encode_message(messages[trial % messages.size()]);
        const int corruptions = 1 + static_cast<int>(rng() % 4);
        for (int c = 0; c < corruptions; ++c) {
            body[rng() % body.size()] = static_cast<uint8_t>(rng());
        }
        Result<Message> decoded = decode_message(body);
        if (decoded.ok()) {
            Result<Message> again = decode_message(encode_message(*decoded));
            ASSERT_TRUE(again.ok()) << again.error();
            ASSERT_TRUE(same(*decoded, *again));
        }
    }
}

TEST(Codec, SchemaHashIsTheSchemaFilesSha256Prefix) {
    std::ifstream in(test::source_dir() / "protocol" / "lightcuts.fbs", std::ios::binary);
    ASSERT_TRUE(in.good());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    unsigned char digest[SHA256_DIGEST_LENGTH];
    SHA256(reinterpret_cast<const unsigned char*>(text.data()), text.size(), digest);
    uint64_t expected = 0;
    for (int i = 0; i < 8; ++i) expected = (expected << 8) | digest[i];
    EXPECT_EQ(schema_hash(), expected);
}

}  // namespace
}  // namespace lc

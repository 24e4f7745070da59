// FrameDecoder: a push parser tested without sockets.
#include "protocol/frame_decoder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <new>
#include <random>
#include <stdexcept>

// Records the largest single allocation while armed, so tests can prove that a
// header announcing a huge frame does not make the decoder allocate it.
namespace {
std::atomic<bool> g_tracking{false};
std::atomic<size_t> g_largest_allocation{0};
}  // namespace

// GCC cannot see that these replacements pair malloc with free on purpose.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
    if (g_tracking.load(std::memory_order_relaxed)) {
        size_t seen = g_largest_allocation.load(std::memory_order_relaxed);
        while (size > seen && !g_largest_allocation.compare_exchange_weak(seen, size)) {
        }
    }
    if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
    throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace lc {
namespace {

using Frames = std::vector<std::vector<uint8_t>>;

std::vector<uint8_t> pattern(size_t size, uint8_t seed) {
    std::vector<uint8_t> v(size);
    for (size_t i = 0; i < size; ++i) v[i] = static_cast<uint8_t>(seed + i * 31);
    return v;
}

std::vector<uint8_t> header(uint32_t size) {
    return {static_cast<uint8_t>(size), static_cast<uint8_t>(size >> 8),
            static_cast<uint8_t>(size >> 16), static_cast<uint8_t>(size >> 24)};
}

std::vector<uint8_t> concat(const std::vector<std::vector<uint8_t>>& parts) {
    std::vector<uint8_t> out;
    for (const auto& p : parts) out.insert(out.end(), p.begin(), p.end());
    return out;
}

TEST(FrameDecoder, FrameBytesPrependsLittleEndianSize) {
    const auto body = pattern(0x0102, 5);
    const auto framed = frame_bytes(body);
    ASSERT_EQ(framed.size(), body.size() + 4);
    EXPECT_EQ(framed[0], 0x02);
    EXPECT_EQ(framed[1], 0x01);
    EXPECT_EQ(framed[2], 0x00);
    EXPECT_EQ(framed[3], 0x00);
    EXPECT_TRUE(std::equal(body.begin(), body.end(), framed.begin() + 4));
}

TEST(FrameDecoder, DecodesOneWholeFrame) {
    FrameDecoder decoder;
    Frames frames;
    const auto body = pattern(100, 1);
    ASSERT_TRUE(decoder.consume(frame_bytes(body), frames));
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_EQ(frames[0], body);
    EXPECT_EQ(decoder.state(), FrameDecoder::State::kReadingHeader);
    EXPECT_EQ(decoder.buffered_bytes(), 0u);
}

TEST(FrameDecoder, DecodesManyFramesFromOnePush) {
    std::vector<std::vector<uint8_t>> bodies;
    for (uint8_t i = 1; i <= 20; ++i) bodies.push_back(pattern(i * 7u, i));
    std::vector<std::vector<uint8_t>> framed;
    for (const auto& b : bodies) framed.push_back(frame_bytes(b));
    FrameDecoder decoder;
    Frames frames;
    ASSERT_TRUE(decoder.consume(concat(framed), frames));
    EXPECT_EQ(frames, bodies);
}

TEST(FrameDecoder, DecodesByteByByte) {
    const std::vector<std::vector<uint8_t>> bodies{pattern(1, 9), pattern(13, 2), pattern(300, 3)};
    std::vector<std::vector<uint8_t>> framed;
    for (const auto& b : bodies) framed.push_back(frame_bytes(b));
    const auto stream = concat(framed);
    FrameDecoder decoder;
    Frames frames;
    for (size_t i = 0; i < stream.size(); ++i) {
        ASSERT_TRUE(decoder.consume(std::span(&stream[i], 1), frames)) << "byte " << i;
    }
    EXPECT_EQ(frames, bodies);
    EXPECT_EQ(decoder.buffered_bytes(), 0u);
}

TEST(FrameDecoder, HeaderSplitAcrossPushes) {
    const auto body = pattern(40, 4);
    const auto framed = frame_bytes(body);
    for (size_t split = 1; split < 4; ++split) {
        FrameDecoder decoder;
        Frames frames;
        ASSERT_TRUE(decoder.consume(std::span(framed).first(split), frames));
        EXPECT_EQ(decoder.state(), FrameDecoder::State::kReadingHeader);
        EXPECT_EQ(decoder.buffered_bytes(), split);
        EXPECT_TRUE(frames.empty());
        ASSERT_TRUE(decoder.consume(std::span(framed).subspan(split), frames));
        ASSERT_EQ(frames.size(), 1u);
        EXPECT_EQ(frames[0], body);
    }
}

TEST(FrameDecoder, ReportsPartialBodyBytes) {
    const auto framed = frame_bytes(pattern(10, 0));
    FrameDecoder decoder;
    Frames frames;
    ASSERT_TRUE(decoder.consume(std::span(framed).first(7), frames));
    EXPECT_EQ(decoder.state(), FrameDecoder::State::kReadingBody);
    EXPECT_EQ(decoder.buffered_bytes(), 7u);
    EXPECT_TRUE(frames.empty());
}

TEST(FrameDecoder, RandomSplitsReproduceTheFrames) {
    std::mt19937 rng(1234);
    std::vector<std::vector<uint8_t>> bodies;
    for (int i = 0; i < 200; ++i)
        bodies.push_back(pattern(1 + rng() % 700, static_cast<uint8_t>(i)));
    std::vector<std::vector<uint8_t>> framed;
    for (const auto& b : bodies) framed.push_back(frame_bytes(b));
    const auto stream = concat(framed);
    FrameDecoder decoder;
    Frames frames;
    size_t pos = 0;
    while (pos < stream.size()) {
        const size_t take = std::min<size_t>(rng() % 1000, stream.size() - pos);
        ASSERT_TRUE(decoder.consume(std::span(stream).subspan(pos, take), frames));
        pos += take;
    }
    EXPECT_EQ(frames, bodies);
}

TEST(FrameDecoder, AcceptsAFrameExactlyAtTheCap) {
    FrameDecoder decoder(64);
    Frames frames;
    ASSERT_TRUE(decoder.consume(frame_bytes(pattern(64, 1)), frames));
    EXPECT_EQ(frames.size(), 1u);
}

TEST(FrameDecoder, RefusesOverCapHeaderBeforeAllocating) {
    FrameDecoder decoder(64);
    Frames frames;
    g_largest_allocation = 0;
    g_tracking = true;
    const bool ok = decoder.consume(header(0xFFFFFFF0u), frames);
    g_tracking = false;
    EXPECT_FALSE(ok);
    EXPECT_EQ(decoder.state(), FrameDecoder::State::kFailed);
    EXPECT_NE(decoder.error().find("4294967280"), std::string::npos) << decoder.error();
    EXPECT_NE(decoder.error().find("64"), std::string::npos) << decoder.error();
    EXPECT_LT(g_largest_allocation.load(), 1024u);  // only the error text
    EXPECT_EQ(decoder.buffered_bytes(), 0u);

    FrameDecoder just_over(64);
    EXPECT_FALSE(just_over.consume(header(65), frames));
    EXPECT_TRUE(frames.empty());
}

TEST(FrameDecoder, LyingHeaderUnderTheCapDoesNotReserveTheWholeFrame) {
    // 16 MiB announced, 10 bytes sent: memory follows the bytes, not the header.
    FrameDecoder decoder;
    Frames frames;
    auto bytes = header(kDefaultMaxFrameBytes);
    const auto some = pattern(10, 0);
    bytes.insert(bytes.end(), some.begin(), some.end());
    g_largest_allocation = 0;
    g_tracking = true;
    const bool ok = decoder.consume(bytes, frames);
    g_tracking = false;
    EXPECT_TRUE(ok);
    EXPECT_EQ(decoder.buffered_bytes(), 14u);
    EXPECT_LE(g_largest_allocation.load(), 64u * 1024u);
}

TEST(FrameDecoder, RefusesEmptyFrame) {
    FrameDecoder decoder;
    Frames frames;
    EXPECT_FALSE(decoder.consume(header(0), frames));
    EXPECT_EQ(decoder.state(), FrameDecoder::State::kFailed);
    EXPECT_NE(decoder.error().find("empty"), std::string::npos) << decoder.error();
}

TEST(FrameDecoder, StaysFailedAfterAnError) {
    FrameDecoder decoder(16);
    Frames frames;
    // A good frame, then an over-cap header, then another good frame in the same push.
    const auto stream =
        concat({frame_bytes(pattern(3, 1)), header(17), frame_bytes(pattern(3, 2))});
    EXPECT_FALSE(decoder.consume(stream, frames));
    ASSERT_EQ(frames.size(), 1u);  // frames before the bad header are delivered
    const std::string error = decoder.error();
    EXPECT_FALSE(decoder.consume(frame_bytes(pattern(3, 3)), frames));
    EXPECT_EQ(frames.size(), 1u);
    EXPECT_EQ(decoder.state(), FrameDecoder::State::kFailed);
    EXPECT_EQ(decoder.error(), error);
}

TEST(FrameDecoder, EmptyPushIsHarmless) {
    FrameDecoder decoder;
    Frames frames;
    EXPECT_TRUE(decoder.consume({}, frames));
    EXPECT_EQ(decoder.state(), FrameDecoder::State::kReadingHeader);
}

// Reads land in read_buffer(); a read may fill less than it was offered.
void read_into(FrameDecoder& decoder, std::span<const uint8_t> stream, std::mt19937& rng, Frames& frames) {
    size_t pos = 0;
    while (pos < stream.size()) {
        const std::span<uint8_t> into = decoder.read_buffer(1 + rng() % 1000);
        ASSERT_FALSE(into.empty());
        const size_t n = std::min<size_t>({into.size(), 1 + rng() % into.size(), stream.size() - pos});
        std::copy_n(stream.data() + pos, n, into.data());
        pos += n;
        ASSERT_TRUE(decoder.commit(n, frames));
    }
}

TEST(FrameDecoder, ReadsStraightIntoTheFrameBody) {
    std::mt19937 rng(99);
    std::vector<std::vector<uint8_t>> bodies;
    for (int i = 0; i < 200; ++i) bodies.push_back(pattern(1 + rng() % 3000, static_cast<uint8_t>(i)));
    std::vector<std::vector<uint8_t>> framed;
    for (const auto& b : bodies) framed.push_back(frame_bytes(b));
    FrameDecoder decoder;
    Frames frames;
    read_into(decoder, concat(framed), rng, frames);
    EXPECT_EQ(frames, bodies);
    EXPECT_EQ(decoder.state(), FrameDecoder::State::kReadingHeader);
}

TEST(FrameDecoder, ReadBufferNeverReachesPastTheFrame) {
    FrameDecoder decoder;
    Frames frames;
    const auto framed = frame_bytes(pattern(10, 0));
    std::span<uint8_t> into = decoder.read_buffer(1000);
    ASSERT_EQ(into.size(), kFrameHeaderBytes);  // the header first: the next frame's bytes stay in the socket
    std::copy_n(framed.data(), kFrameHeaderBytes, into.data());
    ASSERT_TRUE(decoder.commit(kFrameHeaderBytes, frames));
    into = decoder.read_buffer(1000);
    ASSERT_EQ(into.size(), 10u);
    std::copy_n(framed.data() + kFrameHeaderBytes, 10, into.data());
    ASSERT_TRUE(decoder.commit(10, frames));
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_EQ(frames[0], pattern(10, 0));
}

TEST(FrameDecoder, LyingHeaderCostsAtMostOneRead) {
    FrameDecoder decoder;
    Frames frames;
    const auto announced = header(kDefaultMaxFrameBytes);
    std::copy(announced.begin(), announced.end(), decoder.read_buffer(4).data());
    ASSERT_TRUE(decoder.commit(4, frames));
    g_largest_allocation = 0;
    g_tracking = true;
    const std::span<uint8_t> into = decoder.read_buffer(256 * 1024);
    g_tracking = false;
    EXPECT_EQ(into.size(), 256u * 1024u);
    EXPECT_LE(g_largest_allocation.load(), 256u * 1024u);
}

TEST(FrameDecoder, RecycledFrameStorageHoldsTheNextBody) {
    FrameDecoder decoder;
    Frames frames;
    ASSERT_TRUE(decoder.consume(frame_bytes(pattern(5000, 1)), frames));
    ASSERT_EQ(frames.size(), 1u);
    const uint8_t* storage = frames[0].data();
    decoder.recycle(std::move(frames[0]));
    frames.clear();
    ASSERT_TRUE(decoder.consume(frame_bytes(pattern(3000, 2)), frames));
    ASSERT_EQ(frames.size(), 1u);
    EXPECT_EQ(frames[0].data(), storage);
    EXPECT_EQ(frames[0], pattern(3000, 2));
}

TEST(FrameDecoder, CommitPastTheReadBufferThrows) {
    FrameDecoder decoder;
    Frames frames;
    EXPECT_THROW(decoder.commit(5, frames), std::out_of_range);
}

}  // namespace
}  // namespace lc

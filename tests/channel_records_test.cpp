// Channel records: byte layouts, round trips, push parsing at every split
// point, refusal of bad records, and structural validation of deep trees.
#include "protocol/channel_records.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

namespace lc {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

bool same_light(const SceneLight& x, const SceneLight& y) {
    return x.guid == y.guid && x.type == y.type && x.position == y.position &&
           x.direction == y.direction && x.color == y.color && x.intensity == y.intensity &&
           x.range == y.range && x.inner_cone_angle == y.inner_cone_angle &&
           x.outer_cone_angle == y.outer_cone_angle && x.classic == y.classic;
}

bool same_node(const LightTreeNode& x, const LightTreeNode& y) {
    return x.guid == y.guid && x.type == y.type && x.left == y.left && x.right == y.right &&
           x.representative == y.representative && x.position == y.position &&
           x.direction == y.direction && x.range == y.range &&
           x.spot_cos_inner == y.spot_cos_inner && x.spot_cos_outer == y.spot_cos_outer &&
           x.intensity == y.intensity && x.brightness == y.brightness && x.radius == y.radius &&
           x.falloff_exponent == y.falloff_exponent && x.bbox_min == y.bbox_min &&
           x.bbox_max == y.bbox_max && x.cone_axis == y.cone_axis && x.cone_cos == y.cone_cos &&
           x.flags.mixed_types() == y.flags.mixed_types() && x.flags.indirect() == y.flags.indirect();
}

void expect_same_tree(const LightTree& x, const LightTree& y) {
    ASSERT_EQ(x.nodes.size(), y.nodes.size());
    EXPECT_EQ(x.leaf_count, y.leaf_count);
    for (size_t i = 0; i < x.nodes.size(); ++i) {
        EXPECT_TRUE(same_node(x.nodes[i], y.nodes[i])) << "node " << i;
    }
}

std::vector<SceneLight> sample_lights() {
    SceneLight point;
    point.guid = Guid{1, 2, 3, 4};
    point.position = {1.5f, -2.0f, 1e6f};
    point.color = {1.0f, 0.5f, 0.25f};
    point.intensity = 5000.0f;
    point.range = 250.0f;

    SceneLight spot;
    spot.guid = Guid{5, 6, 7, 8};
    spot.type = LightType::kSpot;
    spot.position = {0.0f, 10.0f, 0.0f};
    spot.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    spot.color = {0.0f, 1.0f, 0.0f};
    spot.intensity = 1e-3f;
    spot.inner_cone_angle = 0.1f;
    spot.outer_cone_angle = std::numbers::pi_v<float> / 2.0f;
    spot.classic = true;

    SceneLight sun;
    sun.guid = Guid{9, 10, 11, 12};
    sun.type = LightType::kDirectional;
    sun.direction = {0.0f, 0.0f, -1.0f};
    sun.intensity = 0.0f;
    return {point, spot, sun};
}

LightTreeNode leaf(uint32_t id, glm::vec3 position, float brightness, float radius) {
    LightTreeNode n;
    n.guid = Guid{0x1EAF, 0, 0, id};
    n.position = position;
    n.intensity = glm::vec3(brightness);
    n.brightness = brightness;
    n.radius = radius;
    n.bbox_min = n.bbox_max = position;
    n.cone_cos = -1.0f;
    return n;
}

LightTreeNode cluster(const LightTree& tree, int32_t left, int32_t right, float radius) {
    const LightTreeNode& l = tree.nodes[static_cast<size_t>(left)];
    const LightTreeNode& r = tree.nodes[static_cast<size_t>(right)];
    LightTreeNode n = l;  // thesis rule: the parent takes its first child's representative
    n.guid = Guid::combine(l.guid, r.guid);
    n.left = left;
    n.right = right;
    n.intensity = l.intensity + r.intensity;
    n.brightness = l.brightness + r.brightness;
    n.radius = radius;
    n.bbox_min = glm::min(l.bbox_min, r.bbox_min);
    n.bbox_max = glm::max(l.bbox_max, r.bbox_max);
    return n;
}

// The thesis's Figure 9.1 tree (SPEC §4), in breadth-first order:
//   0: root 27500 {1, 2}    1: 17500 {3, 4}    2: 10000 {5, 6}    3: 12500 {7, 8}
//   4: (-300,150)  5: (0,0)  6: (150,0)  7: (-300,0)  8: (-225,-45)
LightTree thesis_tree() {
    LightTree tree;
    tree.nodes.resize(9);
    tree.nodes[4] = leaf(4, {-300, 150, 150}, 5000, 250);
    tree.nodes[5] = leaf(5, {0, 0, 150}, 5000, 250);
    tree.nodes[6] = leaf(6, {150, 0, 150}, 5000, 250);
    tree.nodes[7] = leaf(7, {-300, 0, 150}, 5000, 250);
    tree.nodes[8] = leaf(8, {-225, -45, 150}, 7500, 250);
    for (int32_t i = 4; i < 9; ++i) tree.nodes[static_cast<size_t>(i)].representative = i;
    tree.nodes[3] = cluster(tree, 7, 8, 337.464f);
    tree.nodes[2] = cluster(tree, 5, 6, 400.0f);
    tree.nodes[1] = cluster(tree, 3, 4, 400.0f);
    tree.nodes[0] = cluster(tree, 1, 2, 700.0f);
    tree.leaf_count = 5;
    return tree;
}

// A tree with every light type, a coloured light, a directional leaf and a
// mixed-type junction at the root.
LightTree mixed_tree() {
    LightTree tree;
    tree.nodes.resize(5);
    LightTreeNode spot = leaf(3, {1, 2, 3}, 10, 50);
    spot.type = LightType::kSpot;
    spot.direction = {0, -1, 0};
    spot.intensity = {10, 5, 0};
    spot.spot_cos_inner = 0.9f;
    spot.spot_cos_outer = 0.7f;
    spot.range = 40.0f;
    spot.cone_axis = {0, -1, 0};
    spot.cone_cos = 1.0f;
    LightTreeNode sun = leaf(4, {0, 0, 0}, 2, kUnboundedRadius);
    sun.type = LightType::kDirectional;
    sun.direction = {0, 0, -1};
    LightTreeNode dark = leaf(2, {5, 5, 5}, 0, 0);
    dark.falloff_exponent = 0.0f;
    tree.nodes[2] = dark;
    tree.nodes[3] = spot;
    tree.nodes[4] = sun;
    for (int32_t i = 2; i < 5; ++i) tree.nodes[static_cast<size_t>(i)].representative = i;
    tree.nodes[1] = cluster(tree, 3, 4, kUnboundedRadius);
    tree.nodes[1].flags.set(kNodeMixedTypes, true);
    tree.nodes[0] = cluster(tree, 1, 2, kUnboundedRadius);
    tree.nodes[0].flags.set(kNodeMixedTypes, true);
    tree.leaf_count = 3;
    return tree;
}

float float_at(const std::vector<uint8_t>& bytes, size_t offset) {
    float v;
    std::memcpy(&v, bytes.data() + offset, 4);
    return v;
}
uint32_t u32_at(const std::vector<uint8_t>& bytes, size_t offset) {
    uint32_t v;
    std::memcpy(&v, bytes.data() + offset, 4);
    return v;
}
int32_t i32_at(const std::vector<uint8_t>& bytes, size_t offset) {
    return static_cast<int32_t>(u32_at(bytes, offset));
}
void put_float(std::vector<uint8_t>& bytes, size_t offset, float v) {
    std::memcpy(bytes.data() + offset, &v, 4);
}
void put_i32(std::vector<uint8_t>& bytes, size_t offset, int32_t v) {
    std::memcpy(bytes.data() + offset, &v, 4);
}

// ---- layouts -----------------------------------------------------------------

TEST(ChannelRecords, RecordSizesMatchTheSchema) {
    EXPECT_EQ(scene_record_bytes(), 72u);
    EXPECT_EQ(result_record_bytes(), 92u + 8u + 80u);
}

TEST(ChannelRecords, SceneRecordLayout) {
    const auto lights = sample_lights();
    const auto bytes = encode_scene_channel(lights);
    ASSERT_EQ(bytes.size(), 4 + 3 * 72u);
    EXPECT_EQ(i32_at(bytes, 0), 3);
    const size_t spot = 4 + 72;                                    // second record
    EXPECT_EQ(u32_at(bytes, spot + 0), 5u);                        // guid.a
    EXPECT_EQ(u32_at(bytes, spot + 12), 8u);                       // guid.d
    EXPECT_EQ(float_at(bytes, spot + 20), 10.0f);                  // position.y
    EXPECT_EQ(float_at(bytes, spot + 28), lights[1].direction.x);  // direction.x
    EXPECT_EQ(float_at(bytes, spot + 44), 1.0f);                   // color.y
    EXPECT_EQ(float_at(bytes, spot + 52), 1e-3f);                  // intensity
    EXPECT_EQ(float_at(bytes, spot + 56), 0.0f);                   // range
    EXPECT_EQ(float_at(bytes, spot + 60), 0.1f);                   // inner_cone_angle
    EXPECT_EQ(bytes[spot + 68], 1u);                               // light_type: spot
    EXPECT_EQ(bytes[spot + 69], 1u);                               // flags: classic
}

TEST(ChannelRecords, ResultRecordLayoutFollowsUnrealFields) {
    const LightTree tree = mixed_tree();
    const auto bytes = encode_result_channel(tree);
    ASSERT_EQ(bytes.size(), 4 + 5 * 180u);
    EXPECT_EQ(i32_at(bytes, 0), 5);

    // Node 1: a cluster whose representative is the spot leaf (node 3).
    const size_t c = 4 + 1 * 180;
    EXPECT_EQ(u32_at(bytes, c + 16), 1u | (1u << 8));  // light_flags: cluster, spot
    EXPECT_EQ(float_at(bytes, c + 20), 1.0f);          // position.x
    EXPECT_EQ(float_at(bytes, c + 32), 1.0f);          // position.w: positional
    EXPECT_EQ(float_at(bytes, c + 40), -1.0f);         // direction.y
    EXPECT_EQ(float_at(bytes, c + 48), 0.0f);          // direction.w
    // color = intensity / brightness = (12, 7, 2) / 12
    EXPECT_FLOAT_EQ(float_at(bytes, c + 52), 1.0f);
    EXPECT_FLOAT_EQ(float_at(bytes, c + 56), 7.0f / 12.0f);
    EXPECT_FLOAT_EQ(float_at(bytes, c + 60), 2.0f / 12.0f);
    EXPECT_EQ(float_at(bytes, c + 64), 1.0f);              // color.a
    EXPECT_EQ(float_at(bytes, c + 68), 12.0f);             // brightness
    EXPECT_EQ(float_at(bytes, c + 72), 0.0f);              // LightSourceRadius
    EXPECT_EQ(float_at(bytes, c + 76), 0.0f);              // LightSourceLength
    EXPECT_EQ(float_at(bytes, c + 80), 1.0f);              // IndirectLightingScale
    EXPECT_EQ(float_at(bytes, c + 84), 1.0f);              // IndirectLightingSaturation
    EXPECT_EQ(float_at(bytes, c + 88), 2.0f);              // ShadowExponent
    EXPECT_EQ(float_at(bytes, c + 92), kUnboundedRadius);  // FPointLightData.Radius
    EXPECT_EQ(float_at(bytes, c + 96), 2.0f);              // FalloffExponent
    EXPECT_EQ(i32_at(bytes, c + 100), 3);                  // left
    EXPECT_EQ(i32_at(bytes, c + 104), 4);                  // right
    EXPECT_EQ(i32_at(bytes, c + 108), 3);                  // representative
    EXPECT_EQ(float_at(bytes, c + 112), 12.0f);            // intensity.r
    EXPECT_EQ(float_at(bytes, c + 116), 7.0f);             // intensity.g
    EXPECT_EQ(float_at(bytes, c + 168), 0.9f);             // spot_cos_inner
    EXPECT_EQ(float_at(bytes, c + 172), 0.7f);             // spot_cos_outer
    EXPECT_EQ(bytes[c + 176], 1u);                         // light_type: spot
    EXPECT_EQ(bytes[c + 177], 1u);                         // flags: mixed types

    // Node 4: a directional leaf has position.w = 0 and no cluster bit.
    const size_t d = 4 + 4 * 180;
    EXPECT_EQ(u32_at(bytes, d + 16), 2u << 8);
    EXPECT_EQ(float_at(bytes, d + 32), 0.0f);
    EXPECT_EQ(i32_at(bytes, d + 100), -1);
    EXPECT_EQ(i32_at(bytes, d + 104), -1);
    // Node 2: zero brightness gives a zero colour, not NaN.
    const size_t z = 4 + 2 * 180;
    EXPECT_EQ(float_at(bytes, z + 52), 0.0f);
    EXPECT_EQ(float_at(bytes, z + 64), 1.0f);
}

// ---- round trips ----------------------------------------------------------------

TEST(ChannelRecords, SceneRoundTrip) {
    const auto lights = sample_lights();
    auto decoded = decode_scene_channel(encode_scene_channel(lights));
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    ASSERT_EQ(decoded->size(), lights.size());
    for (size_t i = 0; i < lights.size(); ++i) EXPECT_TRUE(same_light(lights[i], (*decoded)[i]));

    auto empty = decode_scene_channel(encode_scene_channel({}));
    ASSERT_TRUE(empty.ok()) << empty.error();
    EXPECT_TRUE(empty->empty());
}

TEST(ChannelRecords, ResultRoundTrip) {
    for (const LightTree& tree : {thesis_tree(), mixed_tree(), LightTree{}}) {
        ASSERT_TRUE(validate_tree(tree).ok()) << validate_tree(tree).error();
        auto decoded = decode_result_channel(encode_result_channel(tree));
        ASSERT_TRUE(decoded.ok()) << decoded.error();
        expect_same_tree(tree, *decoded);
    }
}

TEST(ChannelRecords, IncrementalEncoderMatchesWholeEncoder) {
    const LightTree tree = thesis_tree();
    auto bytes = encode_result_prefix(9);
    append_result_records(tree, 0, 4, bytes);
    append_result_records(tree, 4, 0, bytes);
    append_result_records(tree, 4, 5, bytes);
    EXPECT_EQ(bytes, encode_result_channel(tree));
    EXPECT_THROW(append_result_records(tree, 5, 5, bytes), std::out_of_range);
}

TEST(ChannelRecords, RecordsWrittenInPlaceMatchTheAppendedOnes) {
    const LightTree tree = thesis_tree();
    std::vector<uint8_t> appended;
    append_result_records(tree, 2, 6, appended);
    std::vector<uint8_t> written(6 * result_record_bytes());
    write_result_records(tree, 2, 6, written);
    EXPECT_EQ(written, appended);
    EXPECT_THROW(write_result_records(tree, 2, 5, written), std::length_error);
    EXPECT_THROW(write_result_records(tree, 8, 6, written), std::out_of_range);
}

TEST(ChannelRecords, ResultReaderDecodesRecordsAtAnyAlignment) {
    const LightTree tree = thesis_tree();
    const auto bytes = encode_result_channel(tree);
    for (size_t shift = 0; shift < 8; ++shift) {
        std::vector<uint8_t> shifted(shift + bytes.size());
        std::copy(bytes.begin(), bytes.end(), shifted.begin() + static_cast<ptrdiff_t>(shift));
        auto decoded = decode_result_channel(std::span(shifted).subspan(shift));
        ASSERT_TRUE(decoded.ok()) << "shift " << shift << ": " << decoded.error();
        expect_same_tree(tree, *decoded);
    }
}

TEST(ChannelRecords, SceneReaderAcceptsEverySplitIntoThreePieces) {
    const auto lights = sample_lights();
    const auto bytes = encode_scene_channel(lights);
    for (size_t i = 0; i <= bytes.size(); ++i) {
        for (size_t j = i; j <= bytes.size(); j += 1) {
            SceneChannelReader reader;
            ASSERT_TRUE(reader.consume(std::span(bytes).first(i)).ok());
            ASSERT_TRUE(reader.consume(std::span(bytes).subspan(i, j - i)).ok());
            ASSERT_TRUE(reader.consume(std::span(bytes).subspan(j)).ok());
            EXPECT_EQ(reader.bytes_seen(), bytes.size());
            auto decoded = reader.finish();
            ASSERT_TRUE(decoded.ok()) << i << "," << j << ": " << decoded.error();
            ASSERT_EQ(decoded->size(), 3u);
            ASSERT_TRUE(same_light((*decoded)[1], lights[1]));
        }
    }
}

TEST(ChannelRecords, ResultReaderAcceptsEverySplitAndByteByByte) {
    const LightTree tree = thesis_tree();
    const auto bytes = encode_result_channel(tree);
    for (size_t i = 0; i <= bytes.size(); ++i) {
        ResultChannelReader reader;
        ASSERT_TRUE(reader.consume(std::span(bytes).first(i)).ok());
        ASSERT_TRUE(reader.consume(std::span(bytes).subspan(i)).ok());
        auto decoded = reader.finish();
        ASSERT_TRUE(decoded.ok()) << "split at " << i << ": " << decoded.error();
        expect_same_tree(tree, *decoded);
    }
    ResultChannelReader reader;
    for (size_t i = 0; i < bytes.size(); ++i) {
        ASSERT_TRUE(reader.consume(std::span(&bytes[i], 1)).ok());
        EXPECT_EQ(reader.nodes_received(), i + 1 < 4 ? 0 : (i + 1 - 4) / 180);
    }
    EXPECT_EQ(reader.nodes_expected(), 9);
    auto decoded = reader.finish();
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    expect_same_tree(tree, *decoded);
}

// ---- refusals --------------------------------------------------------------------

std::string scene_error(const std::vector<SceneLight>& lights) {
    auto decoded = decode_scene_channel(encode_scene_channel(lights));
    return decoded.ok() ? std::string("(accepted)") : decoded.error();
}

TEST(ChannelRecords, BadSceneLightsAreRefusedNamingLightAndField) {
    struct Case {
        const char* field;
        void (*corrupt)(SceneLight&);
    };
    const std::vector<Case> cases{
        {"position", [](SceneLight& l) { l.position.y = kNaN; }},
        {"direction", [](SceneLight& l) { l.direction.z = kInf; }},
        {"color", [](SceneLight& l) { l.color.x = -0.5f; }},
        {"color", [](SceneLight& l) { l.color.z = kNaN; }},
        {"intensity", [](SceneLight& l) { l.intensity = -1.0f; }},
        {"intensity", [](SceneLight& l) { l.intensity = kInf; }},
        {"range", [](SceneLight& l) { l.range = -3.0f; }},
        {"range", [](SceneLight& l) { l.range = kNaN; }},
        {"cone angles", [](SceneLight& l) { l.inner_cone_angle = kNaN; }},
        {"not unit length",
         [](SceneLight& l) {
             l.direction = {0.0f, -1.01f, 0.0f};
         }},
        {"not unit length",
         [](SceneLight& l) {
             l.direction = {0.0f, 0.0f, 0.0f};
         }},
        {"cone angles", [](SceneLight& l) { l.inner_cone_angle = l.outer_cone_angle; }},
        {"cone angles", [](SceneLight& l) { l.inner_cone_angle = -0.1f; }},
        {"cone angles", [](SceneLight& l) { l.outer_cone_angle = 1.6f; }},
    };
    for (const Case& c : cases) {
        auto lights = sample_lights();
        c.corrupt(lights[1]);  // the spot light
        const std::string error = scene_error(lights);
        EXPECT_NE(error.find("light 1 "), std::string::npos) << error;
        EXPECT_NE(error.find(lights[1].guid.to_hex()), std::string::npos) << error;
        EXPECT_NE(error.find(c.field), std::string::npos) << c.field << ": " << error;
    }
    // A directional light also needs a unit direction.
    auto lights = sample_lights();
    lights[2].direction = {0.0f, 0.0f, -2.0f};
    EXPECT_NE(scene_error(lights).find("light 2 "), std::string::npos);
    // A point light's direction and cone angles are unused and not checked beyond finiteness.
    lights = sample_lights();
    lights[0].direction = {0.0f, 0.0f, 0.0f};
    lights[0].inner_cone_angle = 3.0f;
    EXPECT_EQ(scene_error(lights), "(accepted)");
}

TEST(ChannelRecords, UnknownSceneTypeAndFlagsAreRefused) {
    auto bytes = encode_scene_channel(sample_lights());
    auto bad_type = bytes;
    bad_type[4 + 72 + 68] = 4;  // 3 is oriented, the last known type
    auto decoded = decode_scene_channel(bad_type);
    ASSERT_FALSE(decoded.ok());
    EXPECT_NE(decoded.error().find("light 1 "), std::string::npos) << decoded.error();
    EXPECT_NE(decoded.error().find("light_type 4"), std::string::npos) << decoded.error();
    auto bad_flags = bytes;
    bad_flags[4 + 69] = 0x80;
    decoded = decode_scene_channel(bad_flags);
    ASSERT_FALSE(decoded.ok());
    EXPECT_NE(decoded.error().find("light 0 "), std::string::npos) << decoded.error();
    EXPECT_NE(decoded.error().find("flags"), std::string::npos) << decoded.error();
}

TEST(ChannelRecords, BadCountsAreRefused) {
    std::vector<uint8_t> negative(4);
    put_i32(negative, 0, -5);
    SceneChannelReader reader;
    Status status = reader.consume(negative);
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.error().find("-5"), std::string::npos) << status.error();
    EXPECT_NE(status.error().find("negative"), std::string::npos) << status.error();
    // The reader stays failed.
    EXPECT_FALSE(reader.consume(encode_scene_channel(sample_lights())).ok());
    EXPECT_FALSE(reader.finish().ok());

    std::vector<uint8_t> too_many(4);
    put_i32(too_many, 0, static_cast<int32_t>(kMaxSceneLights + 1));
    auto decoded = decode_scene_channel(too_many);
    ASSERT_FALSE(decoded.ok());
    EXPECT_NE(decoded.error().find("exceeds the limit of 16777216"), std::string::npos)
        << decoded.error();

    std::vector<uint8_t> too_many_nodes(4);
    put_i32(too_many_nodes, 0, std::numeric_limits<int32_t>::max());
    auto tree = decode_result_channel(too_many_nodes);
    ASSERT_FALSE(tree.ok());
    EXPECT_NE(tree.error().find("exceeds the limit"), std::string::npos) << tree.error();
}

TEST(ChannelRecords, ShortAndOverlongChannelsAreRefused) {
    const auto lights = sample_lights();
    auto bytes = encode_scene_channel(lights);
    put_i32(bytes, 0, 5);
    auto decoded = decode_scene_channel(bytes);
    ASSERT_FALSE(decoded.ok());
    EXPECT_NE(decoded.error().find("channel ended after 3 of 5 records"), std::string::npos)
        << decoded.error();

    // A count announcing the maximum, followed by one record: refused at finish().
    bytes = encode_scene_channel({lights.data(), 1});
    put_i32(bytes, 0, static_cast<int32_t>(kMaxSceneLights));
    decoded = decode_scene_channel(bytes);
    ASSERT_FALSE(decoded.ok());
    EXPECT_NE(decoded.error().find("after 1 of 16777216 records"), std::string::npos);

    bytes = encode_scene_channel(lights);
    bytes.erase(bytes.end() - 10, bytes.end());
    decoded = decode_scene_channel(bytes);
    ASSERT_FALSE(decoded.ok());
    EXPECT_NE(decoded.error().find("after 2 of 3 records"), std::string::npos) << decoded.error();
    EXPECT_NE(decoded.error().find("62 bytes of a partial record"), std::string::npos);

    decoded = decode_scene_channel(std::vector<uint8_t>{3, 0});
    ASSERT_FALSE(decoded.ok());
    EXPECT_NE(decoded.error().find("2 of the 4 bytes"), std::string::npos) << decoded.error();

    bytes = encode_scene_channel(lights);
    bytes.push_back(0);
    decoded = decode_scene_channel(bytes);
    ASSERT_FALSE(decoded.ok());
    EXPECT_NE(decoded.error().find("1 bytes after its 3 records"), std::string::npos)
        << decoded.error();

    auto tree_bytes = encode_result_channel(thesis_tree());
    tree_bytes.insert(tree_bytes.end(), {1, 2, 3});
    auto tree = decode_result_channel(tree_bytes);
    ASSERT_FALSE(tree.ok());
    EXPECT_NE(tree.error().find("after its 9 records"), std::string::npos) << tree.error();
}

// The reader that keeps no nodes (bake's) refuses what the decoding one refuses, with the same words.
std::string validate_only_error(std::span<const uint8_t> bytes) {
    ResultChannelReader reader(TreeImport::kValidateOnly);
    Status status = reader.consume(bytes);
    if (status) status = reader.finish_validation();
    return status ? std::string("(accepted)") : status.error();
}

std::string result_error(const std::vector<uint8_t>& bytes) {
    auto decoded = decode_result_channel(bytes);
    const std::string error = decoded.ok() ? std::string("(accepted)") : decoded.error();
    EXPECT_EQ(validate_only_error(bytes), error);
    return error;
}

TEST(ChannelRecords, BadResultRecordsAreRefusedNamingNodeAndField) {
    const auto good = encode_result_channel(mixed_tree());
    ASSERT_EQ(result_error(good), "(accepted)");
    auto at = [](size_t node, size_t offset) { return 4 + node * 180 + offset; };
    struct Case {
        size_t node;
        const char* expected;
        void (*corrupt)(std::vector<uint8_t>&, size_t base);
    };
    const std::vector<Case> cases{
        {0, "child index 5", [](auto& b, size_t o) { put_i32(b, o + 104, 5); }},
        {1, "child index 0", [](auto& b, size_t o) { put_i32(b, o + 100, 0); }},
        {1, "only one child", [](auto& b, size_t o) { put_i32(b, o + 104, -1); }},
        {0, "representative 7", [](auto& b, size_t o) { put_i32(b, o + 108, 7); }},
        {3, "intensity", [](auto& b, size_t o) { put_float(b, o + 116, -1.0f); }},
        {3, "intensity", [](auto& b, size_t o) { put_float(b, o + 112, kNaN); }},
        {3, "brightness", [](auto& b, size_t o) { put_float(b, o + 68, kInf); }},
        {3, "position", [](auto& b, size_t o) { put_float(b, o + 24, kNaN); }},
        {3, "radius", [](auto& b, size_t o) { put_float(b, o + 92, kNaN); }},
        {3, "falloff_exponent", [](auto& b, size_t o) { put_float(b, o + 96, -2.0f); }},
        {3, "range", [](auto& b, size_t o) { put_float(b, o + 164, -1.0f); }},
        {3, "bounding box", [](auto& b, size_t o) { put_float(b, o + 124, 100.0f); }},
        {3, "cone_cos", [](auto& b, size_t o) { put_float(b, o + 160, 1.5f); }},
        {3, "not unit length", [](auto& b, size_t o) { put_float(b, o + 40, -0.5f); }},
        {3, "spot cosines", [](auto& b, size_t o) { put_float(b, o + 172, 0.95f); }},
        {3, "light_type 4",
         [](auto& b, size_t o) {
             b[o + 176] = 4;
             b[o + 17] = 4;
         }},
        {3, "disagrees", [](auto& b, size_t o) { b[o + 176] = 0; }},
        {3, "says cluster", [](auto& b, size_t o) { b[o + 16] |= 1; }},
        {1, "says leaf", [](auto& b, size_t o) { b[o + 16] &= 0xFE; }},
        {4, "position.w", [](auto& b, size_t o) { put_float(b, o + 32, 1.0f); }},
        {3, "unknown bits", [](auto& b, size_t o) { b[o + 18] = 1; }},
        {3, "unknown bits", [](auto& b, size_t o) { b[o + 177] = 2; }},
    };
    for (const Case& c : cases) {
        auto bytes = good;
        c.corrupt(bytes, at(c.node, 0));
        const std::string error = result_error(bytes);
        EXPECT_NE(error.find("node " + std::to_string(c.node) + ":"), std::string::npos)
            << c.expected << ": " << error;
        EXPECT_NE(error.find(c.expected), std::string::npos) << c.expected << ": " << error;
    }
    // The count must be sane before records: a child index refers to the count.
    auto bytes = good;
    put_i32(bytes, 0, -1);
    EXPECT_NE(result_error(bytes).find("negative"), std::string::npos);
}

// Issue 14, item 5: a node whose normalised colour (intensity / brightness)
// overflows was accepted, then written with an infinite FLightData colour that
// the reader itself refuses. Whatever decodes must encode and decode again to
// the same tree.
TEST(ChannelRecords, NodeWhoseColourWouldOverflowIsRefusedAtDecode) {
    const auto good = encode_result_channel(mixed_tree());
    const size_t node3 = 4 + 3 * 180;
    auto bytes = good;
    put_float(bytes, node3 + 68, 7.7e-41f);  // FLightData.brightness, subnormal
    put_float(bytes, node3 + 112, 1.1e4f);   // LightcutsNodeRecord.intensity.x
    const std::string error = result_error(bytes);
    EXPECT_NE(error.find("node 3:"), std::string::npos) << error;
    EXPECT_NE(error.find("normalised colour"), std::string::npos) << error;

    // A small but representable quotient still decodes, and survives a round trip.
    bytes = good;
    put_float(bytes, node3 + 68, 1e-30f);
    put_float(bytes, node3 + 112, 1e-28f);
    Result<LightTree> once = decode_result_channel(bytes);
    ASSERT_TRUE(once.ok()) << once.error();
    Result<LightTree> twice = decode_result_channel(encode_result_channel(*once));
    ASSERT_TRUE(twice.ok()) << twice.error();
    expect_same_tree(*once, *twice);
}

// ---- tree structure -------------------------------------------------------------

std::string tree_error(const LightTree& tree) {
    Status status = validate_tree(tree);
    return status.ok() ? std::string("(valid)") : status.error();
}

TEST(ChannelRecords, ValidateTreeRefusesBrokenStructure) {
    EXPECT_EQ(tree_error(thesis_tree()), "(valid)");
    EXPECT_EQ(tree_error(LightTree{}), "(valid)");

    LightTree two_parents = thesis_tree();
    two_parents.nodes[2].left = 3;  // node 3 now also hangs under node 2
    EXPECT_NE(tree_error(two_parents).find("node 3 has more than one parent"), std::string::npos)
        << tree_error(two_parents);

    LightTree orphan_only = thesis_tree();
    orphan_only.nodes.push_back(leaf(9, {0, 0, 0}, 1, 1));
    orphan_only.nodes.back().representative = 9;
    orphan_only.leaf_count = 6;
    EXPECT_NE(tree_error(orphan_only).find("node 9 has no parent"), std::string::npos)
        << tree_error(orphan_only);

    LightTree rep_not_leaf = thesis_tree();
    rep_not_leaf.nodes[0].representative = 3;
    EXPECT_NE(tree_error(rep_not_leaf).find("node 0: representative 3 is not a leaf"),
              std::string::npos)
        << tree_error(rep_not_leaf);

    LightTree rep_outside = thesis_tree();
    rep_outside.nodes[2].representative = 7;  // a leaf, but under node 1
    EXPECT_NE(tree_error(rep_outside).find("node 2: representative 7 is outside its subtree"),
              std::string::npos)
        << tree_error(rep_outside);

    LightTree leaf_rep = thesis_tree();
    leaf_rep.nodes[5].representative = 6;
    EXPECT_NE(tree_error(leaf_rep).find("node 5: a leaf must represent itself"), std::string::npos);

    LightTree wrong_count = thesis_tree();
    wrong_count.leaf_count = 4;
    EXPECT_NE(tree_error(wrong_count).find("4 leaves"), std::string::npos);

    LightTree backwards = thesis_tree();
    backwards.nodes[3].left = 1;
    EXPECT_NE(tree_error(backwards).find("node 3: child index 1"), std::string::npos)
        << tree_error(backwards);

    LightTree same_child = thesis_tree();
    same_child.nodes[3].right = 7;
    EXPECT_NE(tree_error(same_child).find("both children"), std::string::npos);
}

TEST(ChannelRecords, ValidateOnlyReaderChecksTheStructureAndKeepsNoNodes) {
    const LightTree good = thesis_tree();
    const auto bytes = encode_result_channel(good);
    ResultChannelReader reader(TreeImport::kValidateOnly);
    // Split mid-record: the partial record waits for the rest, as in the decoding reader.
    ASSERT_TRUE(reader.consume(std::span(bytes).first(400)).ok());
    ASSERT_TRUE(reader.consume(std::span(bytes).subspan(400)).ok());
    EXPECT_EQ(reader.nodes_received(), good.nodes.size());
    ASSERT_TRUE(reader.finish_validation().ok());
    EXPECT_EQ(reader.leaf_count(), good.leaf_count);
    EXPECT_FALSE(reader.finish().ok());  // it kept no tree to hand out

    LightTree two_parents = thesis_tree();
    two_parents.nodes[2].left = 3;
    LightTree rep_outside = thesis_tree();
    rep_outside.nodes[2].representative = 7;
    LightTree indirect_mixed = thesis_tree();
    indirect_mixed.nodes[3].flags.set(kNodeIndirect, true);
    for (const LightTree& broken : {two_parents, rep_outside, indirect_mixed}) {
        const auto broken_bytes = encode_result_channel(broken);
        const std::string error = result_error(broken_bytes);
        EXPECT_NE(error, "(accepted)");
        EXPECT_EQ(validate_only_error(broken_bytes), error);
    }

    ResultChannelReader decoding;
    ASSERT_TRUE(decoding.consume(bytes).ok());
    EXPECT_FALSE(decoding.finish_validation().ok());  // a decoding reader hands out its tree with finish()
}

// Breadth-first chain: node 2k is a cluster {2k+1 (leaf), 2k+2}, the last node a leaf.
LightTree chain_tree(size_t leaves) {
    LightTree tree;
    const size_t n = 2 * leaves - 1;
    tree.nodes.resize(n);
    for (size_t i = 0; i < n; ++i) {
        LightTreeNode& node = tree.nodes[i];
        node.guid = Guid{0, 0, 0, static_cast<uint32_t>(i)};
        node.position = {static_cast<float>(i), 0.0f, 0.0f};
        node.brightness = 1.0f;
        node.intensity = glm::vec3(1.0f);
        const bool is_cluster = i % 2 == 0 && i + 1 < n;
        if (is_cluster) {
            node.left = static_cast<int32_t>(i + 1);
            node.right = static_cast<int32_t>(i + 2);
            node.representative = static_cast<int32_t>(i + 1);
        } else {
            node.representative = static_cast<int32_t>(i);
        }
    }
    tree.leaf_count = static_cast<uint32_t>(leaves);
    return tree;
}

TEST(ChannelRecords, MillionNodeChainValidatesWithoutRecursion) {
    LightTree tree = chain_tree(500001);  // 1,000,001 nodes, depth 500,000
    ASSERT_EQ(tree.nodes.size(), 1000001u);
    EXPECT_EQ(tree_error(tree), "(valid)");
    // The deepest representative is checked too: point it out of its subtree.
    tree.nodes[999998].representative = 1;
    EXPECT_NE(tree_error(tree).find("node 999998: representative 1 is outside its subtree"),
              std::string::npos);
}

TEST(ChannelRecords, DeepChainDecodesThroughTheReader) {
    const LightTree tree = chain_tree(1u << 16);
    const auto bytes = encode_result_channel(tree);
    ResultChannelReader reader;
    // Chunks that split records and the count alike.
    for (size_t pos = 0; pos < bytes.size(); pos += 65537) {
        const size_t take = std::min<size_t>(65537, bytes.size() - pos);
        ASSERT_TRUE(reader.consume(std::span(bytes).subspan(pos, take)).ok());
    }
    auto decoded = reader.finish();
    ASSERT_TRUE(decoded.ok()) << decoded.error();
    EXPECT_EQ(decoded->leaf_count, 1u << 16);
    EXPECT_EQ(decoded->nodes.size(), (2u << 16) - 1);
    EXPECT_TRUE(same_node(decoded->nodes[70000], tree.nodes[70000]));
}

}  // namespace
}  // namespace lc

// Scene and result channel payloads: an int32 LE count, then fixed-layout
// FlatBuffers structs. Readers are push parsers that validate each record the
// moment its last byte arrives.
#include "channel_records.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/geometric.hpp>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "lightcuts_generated.h"
#include "protocol/record_bytes.h"
#include "protocol/tree_links.h"

namespace lc {
namespace {

using namespace records;

// The wire layouts; a change here is a protocol change (bump the version GUIDs).
static_assert(sizeof(fb::SceneLightRecord) == 72);
static_assert(sizeof(fb::FLightData) == 92);
static_assert(sizeof(fb::FPointLightData) == 8);
static_assert(sizeof(fb::LightcutsNodeRecord) == 80);

constexpr size_t kCountBytes = sizeof(int32_t);
constexpr size_t kSceneRecordBytes = sizeof(fb::SceneLightRecord);
constexpr size_t kResultRecordBytes =
    sizeof(fb::FLightData) + sizeof(fb::FPointLightData) + sizeof(fb::LightcutsNodeRecord);
// A lying count must not make us reserve memory for records that never come:
// up front at most this many, then all of them once an eighth has arrived (so
// a 10^6-record channel is not regrown and copied ten times).
constexpr size_t kMaxUpFrontRecords = 1u << 16;
constexpr size_t kReserveAllAfterFraction = 8;

constexpr uint8_t kSceneFlagClassic = 1u << 0;
// FLightData.light_flags carries the node's flags (device/node_flags.h) but
// kNodeMixedTypes, whose bit is Unreal's cluster bit here; the mixed-types bit
// travels in the node record's flags. The indirect and patch bits are
// documented in docs/PROTOCOL.md, not in lightcuts.fbs: the schema file's hash
// is in every dump, and the recorded dumps stay valid.
constexpr uint32_t kLightFlagCluster = 1u << 0;
constexpr uint32_t kLightFlagNodeBits = kNodeIndirect | kNodePatch;
constexpr uint32_t kLightFlagTypeMask = 0xFFu << kNodeTypeShift;
constexpr uint32_t kRecordFlagNodeBits = kNodeMixedTypes;
static_assert((kLightFlagCluster & (kLightFlagNodeBits | kLightFlagTypeMask)) == 0);
static_assert((kLightFlagNodeBits | kRecordFlagNodeBits) == (kNodeMixedTypes | kNodeIndirect | kNodePatch),
              "every node flag travels in one of the two records");
// A VPL leaf's light_source_length is the bounce that left it (a whole number,
// 1 and up; 0: not recorded); every other node's is 0. Documented like the
// indirect bit: the field is Unreal's tube length, which no tree light has.
constexpr float kMaxBounce = float(kMaxRecordedBounce);

// Unreal defaults for the FLightData fields Lightcuts does not use.
constexpr float kIndirectLightingScale = 1.0f;
constexpr float kIndirectLightingSaturation = 1.0f;
constexpr float kShadowExponent = 2.0f;

constexpr float kUnitLengthTolerance = 1e-3f;
// Float rounding of pi/2 and cos(pi/2) must not refuse a legal 90-degree cone.
constexpr float kHalfPi = std::numbers::pi_v<float> / 2.0f;
constexpr float kAngleTolerance = 1e-6f;
constexpr float kCosineTolerance = 1e-6f;

std::string light_label(size_t index, const Guid& guid) {
    return "light " + std::to_string(index) + " (GUID " + guid.to_hex() + ")";
}

bool non_negative3(const glm::vec3& v) { return v.x >= 0.0f && v.y >= 0.0f && v.z >= 0.0f; }
bool unit_length(const glm::vec3& v) {
    return std::abs(glm::length(v) - 1.0f) <= kUnitLengthTolerance;
}
std::string hex(uint32_t v) {
    char text[16];
    std::snprintf(text, sizeof(text), "0x%X", v);
    return text;
}

// ---- scene records -----------------------------------------------------------

fb::SceneLightRecord to_record(const SceneLight& light) {
    return fb::SceneLightRecord(
        to_fb(light.guid), to_fb(light.position), to_fb(light.direction), to_fb(light.color),
        light.intensity, light.range, light.inner_cone_angle, light.outer_cone_angle,
        static_cast<uint8_t>(light.type), light.classic ? kSceneFlagClassic : uint8_t{0}, 0);
}

Result<SceneLight> from_record(const fb::SceneLightRecord& record, size_t index) {
    SceneLight light;
    light.guid = from_fb(record.guid());
    if (record.light_type() >= kLightTypeCount) {
        return make_error(light_label(index, light.guid) + ": light_type " +
                          std::to_string(record.light_type()) + " is unknown");
    }
    if ((record.flags() & ~kSceneFlagClassic) != 0 || record.reserved() != 0) {
        return make_error(light_label(index, light.guid) + ": flags " + hex(record.flags()) +
                          " / reserved " + std::to_string(record.reserved()) +
                          " carry unknown bits");
    }
    light.type = static_cast<LightType>(record.light_type());
    light.position = from_fb(record.position());
    light.direction = from_fb(record.direction());
    light.color = from_fb(record.color());
    light.intensity = record.intensity();
    light.range = record.range();
    light.inner_cone_angle = record.inner_cone_angle();
    light.outer_cone_angle = record.outer_cone_angle();
    light.classic = (record.flags() & kSceneFlagClassic) != 0;
    Status valid = validate_scene_light(light, index);
    if (!valid) return make_error(valid.error());
    return light;
}

// ---- result records ----------------------------------------------------------

struct ResultRecord {
    fb::FLightData light;
    fb::FPointLightData point;
    fb::LightcutsNodeRecord node;
};
static_assert(sizeof(ResultRecord) == kResultRecordBytes, "the three structs lie back to back");

// A record in the channel bytes, read in place when it is aligned as its
// structs are, as FlatBuffers reads its structs: copying 180 bytes to the
// stack and reading fields back across the copy's stores stalled each record
// on store forwarding. A misaligned record (a span cut anywhere) is copied.
class RecordAt {
public:
    explicit RecordAt(const uint8_t* p) {
        if (reinterpret_cast<uintptr_t>(p) % alignof(ResultRecord) == 0) {
            record_ = reinterpret_cast<const ResultRecord*>(p);
        } else {
            record_ = &copy_.emplace(read_struct<ResultRecord>(p));
        }
    }
    const ResultRecord& operator*() const { return *record_; }

private:
    std::optional<ResultRecord> copy_;  // made only for a misaligned record
    const ResultRecord* record_;
};

// FLightData.Color is the normalised colour; the exact RGB travels in the node
// record. A tiny brightness can make the quotient overflow, so the reader
// refuses the nodes whose colour this cannot write finitely.
glm::vec3 normalised_color(const LightTreeNode& n) {
    return n.brightness > 0.0f ? n.intensity / n.brightness : glm::vec3(0.0f);
}

ResultRecord to_record(const LightTreeNode& n) {
    const uint32_t flags = (n.is_leaf() ? 0u : kLightFlagCluster) | (n.flags.bits & kLightFlagNodeBits) |
                           (static_cast<uint32_t>(n.type) << kNodeTypeShift);
    const float w = n.type == LightType::kDirectional ? 0.0f : 1.0f;
    const glm::vec3 color = normalised_color(n);
    const fb::FLightData light(
        to_fb(n.guid), flags, fb::Vec4(n.position.x, n.position.y, n.position.z, w),
        fb::Vec4(n.direction.x, n.direction.y, n.direction.z, 0.0f),
        fb::Vec4(color.x, color.y, color.z, 1.0f), n.brightness, n.source_radius,
        float(n.bounce), kIndirectLightingScale, kIndirectLightingSaturation, kShadowExponent);
    const fb::FPointLightData point(n.radius, n.falloff_exponent);
    const fb::LightcutsNodeRecord node(
        n.left, n.right, n.representative, to_fb(n.intensity), to_fb(n.bbox_min), to_fb(n.bbox_max),
        to_fb(n.cone_axis), n.cone_cos, n.range, n.spot_cos_inner, n.spot_cos_outer,
        static_cast<uint8_t>(n.type), uint8_t(n.flags.bits & kRecordFlagNodeBits), 0);
    return {light, point, node};
}

// The checks of one node's own values: each names what is wrong, or nothing
// (the node's label is added only on failure: every record of a channel
// passes through here).
using NodeProblem = std::optional<std::string>;

NodeProblem link_problem(const LightTreeNode& n, size_t index, size_t node_count) {
    if (static_cast<int>(n.type) >= kLightTypeCount) {
        return "light_type " + std::to_string(static_cast<int>(n.type)) + " is unknown";
    }
    const auto count = static_cast<int64_t>(node_count);
    if ((n.left == kNoChild) != (n.right == kNoChild)) {
        return "has only one child (left " + std::to_string(n.left) + ", right " + std::to_string(n.right) + ")";
    }
    for (int32_t child : {n.left, n.right}) {
        if (child == kNoChild) continue;
        if (child <= static_cast<int64_t>(index) || child >= count) {
            return "child index " + std::to_string(child) + " is outside (" + std::to_string(index) + ", " +
                   std::to_string(node_count) + ")";
        }
    }
    if (n.left != kNoChild && n.left == n.right) return "both children are node " + std::to_string(n.left);
    if (n.representative < 0 || n.representative >= count) {
        return "representative " + std::to_string(n.representative) + " is outside [0, " +
               std::to_string(node_count) + ")";
    }
    return std::nullopt;
}

NodeProblem emission_problem(const LightTreeNode& n) {
    if (!finite3(n.position)) return "position " + vec_text(n.position) + " is not finite";
    if (!finite3(n.direction)) return "direction " + vec_text(n.direction) + " is not finite";
    if (!finite3(n.intensity)) return "intensity " + vec_text(n.intensity) + " is not finite";
    if (!non_negative3(n.intensity)) return "intensity " + vec_text(n.intensity) + " is negative";
    if (!std::isfinite(n.brightness) || n.brightness < 0.0f) {
        return "brightness " + number(n.brightness) + " is not a finite value >= 0";
    }
    if (!finite3(normalised_color(n))) {
        return "intensity " + vec_text(n.intensity) + " over brightness " + number(n.brightness) +
               " overflows the normalised colour";
    }
    if (!std::isfinite(n.radius)) return "radius " + number(n.radius) + " is not finite";
    if (!std::isfinite(n.falloff_exponent) || n.falloff_exponent < 0.0f) {
        return "falloff_exponent " + number(n.falloff_exponent) + " is not a finite value >= 0";
    }
    if (!std::isfinite(n.range) || n.range < 0.0f) {
        return "range " + number(n.range) + " is not a finite value >= 0";
    }
    return std::nullopt;
}

// Patches, their source radius, and a VPL's bounce.
NodeProblem indirect_problem(const LightTreeNode& n) {
    if (n.flags.patch() && !n.flags.indirect()) return "light_flags mark a patch that is not indirect";
    if (!std::isfinite(n.source_radius) || n.source_radius < 0.0f) {
        return "light_source_radius " + number(n.source_radius) + " is not a finite value >= 0";
    }
    if (n.source_radius != 0.0f && !n.flags.patch()) {
        return "light_source_radius " + number(n.source_radius) + " on a light that is not a patch";
    }
    if (n.bounce != 0 && !(n.flags.indirect() && !n.flags.patch() && n.is_leaf())) {
        return "light_source_length " + std::to_string(n.bounce) + " (a bounce) on a node that is not a VPL leaf";
    }
    return std::nullopt;
}

// The bounding box, the orientation cone and the spot cone.
NodeProblem bounds_problem(const LightTreeNode& n) {
    if (!finite3(n.bbox_min) || !finite3(n.bbox_max)) return "bounding box is not finite";
    if (n.bbox_min.x > n.bbox_max.x || n.bbox_min.y > n.bbox_max.y || n.bbox_min.z > n.bbox_max.z) {
        return "bounding box min " + vec_text(n.bbox_min) + " exceeds max " + vec_text(n.bbox_max);
    }
    if (!finite3(n.cone_axis)) return "cone_axis " + vec_text(n.cone_axis) + " is not finite";
    if (!std::isfinite(n.cone_cos) || n.cone_cos < -1.0f || n.cone_cos > 1.0f) {
        return "cone_cos " + number(n.cone_cos) + " is outside [-1, 1]";
    }
    if (!std::isfinite(n.spot_cos_inner) || !std::isfinite(n.spot_cos_outer)) return "spot cosines are not finite";
    const bool oriented = n.type == LightType::kSpot || n.type == LightType::kDirectional ||
                          n.type == LightType::kOriented;
    if (oriented && !n.flags.mixed_types() && !unit_length(n.direction)) {
        return "direction " + vec_text(n.direction) + " of a " + light_type_name(n.type) +
               " light is not unit length";
    }
    if (n.type == LightType::kSpot && !n.flags.mixed_types()) {
        const bool ordered = n.spot_cos_outer >= -kCosineTolerance && n.spot_cos_outer <= n.spot_cos_inner &&
                             n.spot_cos_inner <= 1.0f;
        if (!ordered) {
            return "spot cosines inner " + number(n.spot_cos_inner) + ", outer " + number(n.spot_cos_outer) +
                   " are not 0 <= outer <= inner <= 1";
        }
    }
    return std::nullopt;
}

// Checks one node's own values; structure across nodes is validate_tree's job.
Status validate_node(const LightTreeNode& n, size_t index, size_t node_count) {
    NodeProblem problem = link_problem(n, index, node_count);
    if (!problem) problem = emission_problem(n);
    if (!problem) problem = indirect_problem(n);
    if (!problem) problem = bounds_problem(n);
    if (problem) return make_error(node_label(index) + ": " + *problem);
    return Ok{};
}

// Fills `n` (a default node, already in place in the reader's vector: no copy
// per record) from the record and validates it.
Status from_record(const ResultRecord& r, size_t index, size_t node_count, LightTreeNode& n) {
    const auto who = [index] { return node_label(index); };
    const uint32_t flags = r.light.light_flags();
    const uint32_t type_in_flags = (flags & kLightFlagTypeMask) >> kNodeTypeShift;
    if (r.node.light_type() >= kLightTypeCount) {
        return make_error(who() + ": light_type " + std::to_string(r.node.light_type()) + " is unknown");
    }
    if (type_in_flags != r.node.light_type()) {
        return make_error(who() + ": FLightData.light_flags type " + std::to_string(type_in_flags) +
                          " disagrees with the node record's light_type " +
                          std::to_string(r.node.light_type()));
    }
    if ((flags & ~(kLightFlagCluster | kLightFlagNodeBits | kLightFlagTypeMask)) != 0) {
        return make_error(who() + ": FLightData.light_flags " + hex(flags) + " carries unknown bits");
    }
    if ((r.node.flags() & ~kRecordFlagNodeBits) != 0 || r.node.reserved1() != 0) {
        return make_error(who() + ": node record flags carry unknown bits");
    }
    n.guid = from_fb(r.light.guid());
    n.type = static_cast<LightType>(r.node.light_type());
    n.left = r.node.left();
    n.right = r.node.right();
    n.representative = r.node.representative();
    const fb::Vec4& p = r.light.position();
    const fb::Vec4& d = r.light.direction();
    n.position = {p.x(), p.y(), p.z()};
    n.direction = {d.x(), d.y(), d.z()};
    n.range = r.node.range();
    n.spot_cos_inner = r.node.spot_cos_inner();
    n.spot_cos_outer = r.node.spot_cos_outer();
    n.intensity = from_fb(r.node.intensity());
    n.brightness = r.light.brightness();
    n.radius = r.point.radius();
    n.falloff_exponent = r.point.falloff_exponent();
    n.bbox_min = from_fb(r.node.bbox_min());
    n.bbox_max = from_fb(r.node.bbox_max());
    n.cone_axis = from_fb(r.node.cone_axis());
    n.cone_cos = r.node.cone_cos();
    n.flags.bits = uint8_t((flags & kLightFlagNodeBits) | (r.node.flags() & kRecordFlagNodeBits));
    n.source_radius = r.light.light_source_radius();
    const float bounce = r.light.light_source_length();
    if (!(bounce >= 0.0f && bounce <= kMaxBounce) || bounce != std::floor(bounce)) {
        return make_error(who() + ": light_source_length " + number(bounce) +
                          " is not a bounce (a whole number in [0, 65535])");
    }
    n.bounce = static_cast<uint16_t>(bounce);

    const bool cluster_flag = (flags & kLightFlagCluster) != 0;
    if (cluster_flag == n.is_leaf()) {
        return make_error(who() + ": FLightData.light_flags says " + (cluster_flag ? "cluster" : "leaf") +
                          " but the node has " + (n.is_leaf() ? "no children" : "children"));
    }
    const float expected_w = n.type == LightType::kDirectional ? 0.0f : 1.0f;
    if (p.w() != expected_w) {
        return make_error(who() + ": FLightData.position.w " + number(p.w()) + " should be " +
                          number(expected_w) + " for a " + light_type_name(n.type) + " light");
    }
    const fb::Vec4& c = r.light.color();
    if (!std::isfinite(c.x()) || !std::isfinite(c.y()) || !std::isfinite(c.z()) ||
        !std::isfinite(c.w()) || !std::isfinite(d.w())) {
        return make_error(who() + ": FLightData colour or direction.w is not finite");
    }
    return validate_node(n, index, node_count);
}

// Reserves room for all `expected` records once `arriving` (those received
// plus those in the bytes at hand) make up an eighth of them.
template <typename Record>
void reserve_once_an_eighth_arrives(std::vector<Record>& records, int64_t expected, size_t arriving) {
    if (expected <= 0 || records.capacity() >= static_cast<size_t>(expected)) return;
    if (arriving * kReserveAllAfterFraction >= static_cast<size_t>(expected)) {
        records.reserve(static_cast<size_t>(expected));
    }
}

// Shared push-parser plumbing: feeds whole records from `pending` and `bytes`
// to `on_record`, keeping only a partial record between calls.
template <typename OnCount, typename OnRecord>
Status push_records(std::vector<uint8_t>& pending, int64_t& expected, size_t received,
                    size_t record_bytes, std::span<const uint8_t> bytes, OnCount&& on_count,
                    OnRecord&& on_record) {
    size_t pos = 0;
    // Completes the partial count or record held in `pending`; false when the
    // input ran out first.
    auto fill_pending = [&](size_t want) {
        const size_t take = std::min(want - pending.size(), bytes.size() - pos);
        pending.insert(pending.end(), bytes.data() + pos, bytes.data() + pos + take);
        pos += take;
        return pending.size() == want;
    };

    if (expected < 0) {
        if (!fill_pending(kCountBytes)) return Ok{};
        const int32_t count = get_i32(pending.data());
        pending.clear();
        Status counted = on_count(count);
        if (!counted) return counted;
        expected = count;
    }
    while (true) {
        if (received == static_cast<size_t>(expected)) {
            const size_t extra = pending.size() + (bytes.size() - pos);
            if (extra == 0) return Ok{};
            return make_error("channel carries " + std::to_string(extra) + " bytes after its " +
                              std::to_string(expected) + " records");
        }
        const uint8_t* record = nullptr;
        if (!pending.empty() || bytes.size() - pos < record_bytes) {
            if (!fill_pending(record_bytes)) return Ok{};
            record = pending.data();
        } else {
            record = bytes.data() + pos;
            pos += record_bytes;
        }
        Status accepted = on_record(record, received);
        pending.clear();
        if (!accepted) return accepted;
        ++received;
    }
}

Status check_count(int32_t count, uint32_t limit, const char* what) {
    if (count < 0) {
        return make_error(std::string(what) + " channel count " + std::to_string(count) +
                          " is negative");
    }
    if (static_cast<uint32_t>(count) > limit) {
        return make_error(std::string(what) + " channel count " + std::to_string(count) +
                          " exceeds the limit of " + std::to_string(limit));
    }
    return Ok{};
}

// Checks a channel's count and reserves its first records; `arriving` are the
// records in the bytes at hand (a whole dump is reserved at once).
template <typename Record>
Status accept_count(std::vector<Record>& records, int32_t count, uint32_t limit, const char* what,
                    size_t arriving) {
    Status ok = check_count(count, limit, what);
    if (!ok) return ok;
    records.reserve(std::min<size_t>(static_cast<size_t>(count), kMaxUpFrontRecords));
    reserve_once_an_eighth_arrives(records, count, arriving);
    return ok;
}

std::string short_channel(const char* what, int64_t expected, size_t received,
                          size_t pending_bytes) {
    if (expected < 0) {
        return std::string(what) + " channel ended after " + std::to_string(pending_bytes) +
               " of the 4 bytes of its record count";
    }
    std::string text = std::string(what) + " channel ended after " + std::to_string(received) +
                       " of " + std::to_string(expected) + " records";
    if (pending_bytes > 0) {
        text += " (plus " + std::to_string(pending_bytes) + " bytes of a partial record)";
    }
    return text;
}

void check_node_range(const LightTree& tree, size_t first, size_t count) {
    if (first > tree.nodes.size() || count > tree.nodes.size() - first) {
        throw std::out_of_range("result records: node range outside the tree");
    }
}

void put_count(std::vector<uint8_t>& out, size_t count, uint32_t limit) {
    if (count > limit) throw std::length_error("channel record count exceeds its limit");
    put_u32(out, static_cast<uint32_t>(count));
}

// One pass over the (large) nodes, copying the links the checks need into a
// compact array.
Status validate_tree_structure(const LightTree& tree) {
    std::vector<NodeLinks> links;
    links.reserve(tree.nodes.size());
    for (const LightTreeNode& node : tree.nodes) links.push_back(links_of(node));
    return validate_links(links, tree.leaf_count);
}

}  // namespace

size_t scene_record_bytes() { return kSceneRecordBytes; }
size_t result_record_bytes() { return kResultRecordBytes; }

std::vector<uint8_t> encode_scene_channel(std::span<const SceneLight> lights) {
    std::vector<uint8_t> out;
    out.reserve(kCountBytes + lights.size() * kSceneRecordBytes);
    put_count(out, lights.size(), kMaxSceneLights);
    for (const SceneLight& light : lights) append_struct(out, to_record(light));
    return out;
}

std::vector<uint8_t> encode_result_prefix(uint32_t node_count) {
    std::vector<uint8_t> out;
    put_count(out, node_count, kMaxTreeNodes);
    return out;
}

void append_result_records(const LightTree& tree, size_t first, size_t count,
                           std::vector<uint8_t>& out) {
    check_node_range(tree, first, count);
    const size_t start = out.size();
    out.resize(start + count * kResultRecordBytes);
    write_result_records(tree, first, count, std::span(out).subspan(start));
}

void write_result_records(const LightTree& tree, size_t first, size_t count, std::span<uint8_t> out) {
    check_node_range(tree, first, count);
    if (out.size() != count * kResultRecordBytes) {
        throw std::length_error("write_result_records: output is not the size of the records");
    }
    uint8_t* p = out.data();
    for (size_t i = first; i < first + count; ++i) {
        const ResultRecord r = to_record(tree.nodes[i]);
        p = write_struct(p, r.light);
        p = write_struct(p, r.point);
        p = write_struct(p, r.node);
    }
}

std::vector<uint8_t> encode_result_channel(const LightTree& tree) {
    std::vector<uint8_t> out;
    out.reserve(kCountBytes + tree.nodes.size() * kResultRecordBytes);
    put_count(out, tree.nodes.size(), kMaxTreeNodes);
    append_result_records(tree, 0, tree.nodes.size(), out);
    return out;
}

Status validate_scene_light(const SceneLight& light, size_t index) {
    auto fail = [&](const std::string& what) -> Status {
        return make_error(light_label(index, light.guid) + ": " + what);
    };
    const int type = static_cast<int>(light.type);
    if (type < 0 || type >= kLightTypeCount) {
        return fail("light_type " + std::to_string(type) + " is unknown");
    }
    if (!finite3(light.position)) {
        return fail("position " + vec_text(light.position) + " is not finite");
    }
    if (!finite3(light.direction)) {
        return fail("direction " + vec_text(light.direction) + " is not finite");
    }
    if (!finite3(light.color)) return fail("color " + vec_text(light.color) + " is not finite");
    if (!non_negative3(light.color)) return fail("color " + vec_text(light.color) + " is negative");
    if (!std::isfinite(light.intensity)) {
        return fail("intensity " + number(light.intensity) + " is not finite");
    }
    if (light.intensity < 0.0f)
        return fail("intensity " + number(light.intensity) + " is negative");
    if (!std::isfinite(light.range)) return fail("range " + number(light.range) + " is not finite");
    if (light.range < 0.0f) return fail("range " + number(light.range) + " is negative");
    if (!std::isfinite(light.inner_cone_angle) || !std::isfinite(light.outer_cone_angle)) {
        return fail("cone angles (" + number(light.inner_cone_angle) + ", " +
                    number(light.outer_cone_angle) + ") are not finite");
    }
    const bool oriented = light.type == LightType::kSpot ||
                          light.type == LightType::kDirectional ||
                          light.type == LightType::kOriented;
    if (oriented && !unit_length(light.direction)) {
        return fail("direction " + vec_text(light.direction) + " is not unit length (length " +
                    number(glm::length(light.direction)) + ")");
    }
    if (light.type == LightType::kSpot) {
        const float inner = light.inner_cone_angle;
        const float outer = light.outer_cone_angle;
        if (!(inner >= 0.0f && inner < outer && outer <= kHalfPi + kAngleTolerance)) {
            return fail("cone angles inner " + number(inner) + ", outer " + number(outer) +
                        " break 0 <= inner < outer <= pi/2");
        }
    }
    return Ok{};
}

Status SceneChannelReader::consume(std::span<const uint8_t> bytes) {
    if (failed_) return make_error("scene channel was already refused");
    bytes_seen_ += bytes.size();
    reserve_once_an_eighth_arrives(lights_, expected_, lights_.size() + bytes.size() / kSceneRecordBytes);
    Status status = push_records(
        pending_, expected_, lights_.size(), kSceneRecordBytes, bytes,
        [this, bytes](int32_t count) {
            return accept_count(lights_, count, kMaxSceneLights, "scene", bytes.size() / kSceneRecordBytes);
        },
        [this](const uint8_t* p, size_t index) -> Status {
            Result<SceneLight> light = from_record(read_struct<fb::SceneLightRecord>(p), index);
            if (!light) return make_error(light.error());
            lights_.push_back(light.value());
            return Ok{};
        });
    if (!status) {
        failed_ = true;
        pending_.clear();
        pending_.shrink_to_fit();
    }
    return status;
}

Result<std::vector<SceneLight>> SceneChannelReader::finish() {
    if (failed_) return make_error("scene channel was already refused");
    if (expected_ < 0 || lights_.size() != static_cast<size_t>(expected_) || !pending_.empty()) {
        failed_ = true;
        return make_error(short_channel("scene", expected_, lights_.size(), pending_.size()));
    }
    failed_ = true;  // the lights move out; the reader is spent
    return std::move(lights_);
}

Status ResultChannelReader::consume(std::span<const uint8_t> bytes) {
    if (failed_) return make_error("result channel was already refused");
    const bool keep_nodes = import_ == TreeImport::kNodes;
    const size_t arriving = links_.size() + bytes.size() / kResultRecordBytes;
    if (keep_nodes) reserve_once_an_eighth_arrives(nodes_, expected_, arriving);
    reserve_once_an_eighth_arrives(links_, expected_, arriving);
    // Validation decodes each record into a node either way; without nodes to
    // keep, into this one, which stays in cache, instead of a fresh 140-byte node.
    LightTreeNode scratch;
    Status status = push_records(
        pending_, expected_, links_.size(), kResultRecordBytes, bytes,
        [this, bytes](int32_t count) {
            return accept_count(links_, count, kMaxTreeNodes, "result", bytes.size() / kResultRecordBytes);
        },
        [&](const uint8_t* p, size_t index) -> Status {
            const RecordAt record(p);
            LightTreeNode& node = keep_nodes ? nodes_.emplace_back() : (scratch = LightTreeNode{});
            Status valid = from_record(*record, index, static_cast<size_t>(expected_), node);
            if (!valid) {
                if (keep_nodes) nodes_.pop_back();
                return valid;
            }
            links_.push_back(links_of(node));
            return valid;
        });
    if (!status) {
        failed_ = true;
        pending_.clear();
        pending_.shrink_to_fit();
    }
    return status;
}

Status ResultChannelReader::finish_structure() {
    if (failed_) return make_error("result channel was already refused");
    failed_ = true;  // either refused now or spent
    if (expected_ < 0 || links_.size() != static_cast<size_t>(expected_) || !pending_.empty()) {
        return make_error(short_channel("result", expected_, links_.size(), pending_.size()));
    }
    leaf_count_ = 0;
    for (const NodeLinks& links : links_) leaf_count_ += links.left == kNoChild ? 1u : 0u;
    // Every node's own values were validated as its record arrived; the
    // structure is checked on the links, without reading the nodes again.
    Status valid = validate_links(links_, leaf_count_);
    links_ = std::vector<NodeLinks>();
    return valid;
}

Result<LightTree> ResultChannelReader::finish() {
    if (import_ != TreeImport::kNodes)
        return make_error("result channel reader kept no nodes to finish a tree");
    Status valid = finish_structure();
    if (!valid) return make_error(valid.error());
    LightTree tree;
    tree.nodes = std::move(nodes_);
    tree.leaf_count = leaf_count_;
    return tree;
}

Status ResultChannelReader::finish_validation() {
    if (import_ != TreeImport::kValidateOnly)
        return make_error("result channel reader keeps nodes: finish() the tree");
    return finish_structure();
}

Result<std::vector<SceneLight>> decode_scene_channel(std::span<const uint8_t> bytes) {
    SceneChannelReader reader;
    Status consumed = reader.consume(bytes);
    if (!consumed) return make_error(consumed.error());
    return reader.finish();
}

Result<LightTree> decode_result_channel(std::span<const uint8_t> bytes) {
    ResultChannelReader reader;
    Status consumed = reader.consume(bytes);
    if (!consumed) return make_error(consumed.error());
    return reader.finish();
}

Status validate_tree(const LightTree& tree) {
    const size_t n = tree.nodes.size();
    if (n > kMaxTreeNodes) {
        return make_error("tree has " + std::to_string(n) + " nodes, above the limit of " +
                          std::to_string(kMaxTreeNodes));
    }
    for (size_t i = 0; i < n; ++i) {
        Status valid = validate_node(tree.nodes[i], i, n);
        if (!valid) return valid;
    }
    return validate_tree_structure(tree);
}

}  // namespace lc

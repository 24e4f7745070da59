// The geometry channel's records: fixed-layout FlatBuffers structs after an
// int32 LE count per section, validated the moment their last byte arrives.
#include "protocol/geometry_channel.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "lightcuts_generated.h"
#include "protocol/record_bytes.h"

namespace lc {
namespace {

using namespace records;

// The wire layouts; a change here is a protocol change (bump the version GUID).
static_assert(sizeof(fb::SurfaceMaterialRecord) == 32);
static_assert(sizeof(fb::SurfaceTriangleRecord) == 76);

constexpr size_t kCountBytes = sizeof(int32_t);
constexpr float kUnitLengthTolerance = 1e-3f;
// A lying count must not make us reserve memory for records that never come.
constexpr size_t kMaxUpFrontRecords = 1u << 16;

bool within3(const glm::vec3& v, float lo, float hi) {
    return v.x >= lo && v.y >= lo && v.z >= lo && v.x <= hi && v.y <= hi && v.z <= hi;
}

Result<SurfaceMaterial> from_record(const fb::SurfaceMaterialRecord& r, size_t index) {
    SurfaceMaterial m;
    m.base_color = from_fb(r.base_color());
    m.emission = from_fb(r.emission());
    m.metallic = r.metallic();
    m.roughness = r.roughness();
    const std::string who = "material " + std::to_string(index) + ": ";
    if (!finite3(m.base_color) || !within3(m.base_color, 0.0f, 1.0f))
        return make_error(who + "base colour " + vec_text(m.base_color) + " is not in [0, 1]");
    if (!finite3(m.emission))
        return make_error(who + "emission " + vec_text(m.emission) + " is not finite");
    if (!within3(m.emission, 0.0f, INFINITY))
        return make_error(who + "emission " + vec_text(m.emission) + " is negative");
    if (!(m.metallic >= 0.0f && m.metallic <= 1.0f))
        return make_error(who + "metallic " + number(m.metallic) + " is not in [0, 1]");
    if (!(m.roughness >= 0.0f && m.roughness <= 1.0f))
        return make_error(who + "roughness " + number(m.roughness) + " is not in [0, 1]");
    return m;
}

Result<SurfaceTriangle> from_record(const fb::SurfaceTriangleRecord& r, size_t index,
                                    size_t material_count) {
    SurfaceTriangle t;
    t.positions[0] = from_fb(r.p0());
    t.positions[1] = from_fb(r.p1());
    t.positions[2] = from_fb(r.p2());
    const glm::vec3 normals[3] = {from_fb(r.n0()), from_fb(r.n1()), from_fb(r.n2())};
    t.material = r.material();
    const std::string who = "triangle " + std::to_string(index) + ": ";
    for (const glm::vec3& p : t.positions)
        if (!finite3(p)) return make_error(who + "position " + vec_text(p) + " is not finite");
    if (t.material >= material_count) {
        return make_error(who + "material " + std::to_string(t.material) + " is out of range (" +
                          std::to_string(material_count) + " materials)");
    }
    const bool per_face = std::all_of(std::begin(normals), std::end(normals),
                                      [](const glm::vec3& n) { return n == glm::vec3(0.0f); });
    for (int i = 0; i < 3; ++i) {
        if (per_face) break;
        const glm::vec3& n = normals[i];
        if (!finite3(n) || !(std::abs(glm::length(n) - 1.0f) <= kUnitLengthTolerance))
            return make_error(who + "normal " + vec_text(n) + " is not unit length");
        t.normals[i] = n;
    }
    if (per_face && !is_degenerate(t)) {
        const glm::vec3 face = glm::normalize(triangle_cross(t));
        t.normals[0] = t.normals[1] = t.normals[2] = face;
    }
    return t;
}

std::string count_error(int32_t count, uint32_t limit, const char* what) {
    if (count < 0) return std::string(what) + " count " + std::to_string(count) + " is negative";
    return std::string(what) + " count " + std::to_string(count) + " exceeds the limit of " +
           std::to_string(limit);
}

}  // namespace

size_t geometry_material_record_bytes() { return sizeof(fb::SurfaceMaterialRecord); }
size_t geometry_triangle_record_bytes() { return sizeof(fb::SurfaceTriangleRecord); }

uint64_t geometry_channel_bytes(uint64_t materials, uint64_t triangles) {
    return 2 * kCountBytes + materials * sizeof(fb::SurfaceMaterialRecord) +
           triangles * sizeof(fb::SurfaceTriangleRecord);
}

std::vector<uint8_t> encode_geometry_channel(const SceneGeometry& geometry) {
    std::vector<uint8_t> out;
    out.reserve(geometry_channel_bytes(geometry.materials.size(), geometry.triangles.size()));
    put_u32(out, static_cast<uint32_t>(geometry.materials.size()));
    for (const SurfaceMaterial& m : geometry.materials) {
        append_struct(out, fb::SurfaceMaterialRecord(to_fb(m.base_color), to_fb(m.emission),
                                                     m.metallic, m.roughness));
    }
    put_u32(out, static_cast<uint32_t>(geometry.triangles.size()));
    for (const SurfaceTriangle& t : geometry.triangles) {
        append_struct(out, fb::SurfaceTriangleRecord(
                               to_fb(t.positions[0]), to_fb(t.positions[1]), to_fb(t.positions[2]),
                               to_fb(t.normals[0]), to_fb(t.normals[1]), to_fb(t.normals[2]),
                               t.material));
    }
    return out;
}

void GeometryChannelReader::next_section() {
    section_ = section_ == Section::kMaterials ? Section::kTriangles : Section::kDone;
    expected_ = -1;
    received_ = 0;
}

Status GeometryChannelReader::take_record(const uint8_t* record) {
    if (section_ == Section::kMaterials) {
        Result<SurfaceMaterial> m =
            from_record(read_struct<fb::SurfaceMaterialRecord>(record), received_);
        if (!m) return make_error(m.error());
        geometry_.materials.push_back(*m);
        return Ok{};
    }
    Result<SurfaceTriangle> t = from_record(read_struct<fb::SurfaceTriangleRecord>(record),
                                            received_, geometry_.materials.size());
    if (!t) return make_error(t.error());
    if (is_degenerate(*t)) {
        ++degenerate_;
    } else {
        geometry_.triangles.push_back(*t);
    }
    return Ok{};
}

Status GeometryChannelReader::consume(std::span<const uint8_t> bytes) {
    if (failed_) return make_error("geometry channel was already refused");
    size_t pos = 0;
    // Completes the partial count or record held in `pending_`; false when
    // the input ran out first.
    auto fill_pending = [&](size_t want) {
        const size_t take = std::min(want - pending_.size(), bytes.size() - pos);
        pending_.insert(pending_.end(), bytes.data() + pos, bytes.data() + pos + take);
        pos += take;
        return pending_.size() == want;
    };
    auto fail = [this](const std::string& text) -> Status {
        failed_ = true;
        pending_.clear();
        pending_.shrink_to_fit();
        return make_error(text);
    };
    while (pos < bytes.size() || (section_ != Section::kDone && expected_ == int64_t(received_))) {
        if (section_ == Section::kDone) {
            return fail("geometry channel carries " + std::to_string(bytes.size() - pos) +
                        " bytes after its triangles");
        }
        const bool materials = section_ == Section::kMaterials;
        if (expected_ < 0) {
            if (!fill_pending(kCountBytes)) return Ok{};
            const int32_t count = get_i32(pending_.data());
            pending_.clear();
            const uint32_t limit = materials ? kMaxGeometryMaterials : kMaxGeometryTriangles;
            if (count < 0 || uint32_t(count) > limit)
                return fail(count_error(count, limit, materials ? "material" : "triangle"));
            const size_t up_front = std::min<size_t>(size_t(count), kMaxUpFrontRecords);
            if (materials) geometry_.materials.reserve(up_front);
            else geometry_.triangles.reserve(up_front);
            expected_ = count;
            continue;
        }
        if (expected_ == int64_t(received_)) {
            next_section();
            continue;
        }
        const size_t record_bytes =
            materials ? sizeof(fb::SurfaceMaterialRecord) : sizeof(fb::SurfaceTriangleRecord);
        const uint8_t* record = nullptr;
        if (!pending_.empty() || bytes.size() - pos < record_bytes) {
            if (!fill_pending(record_bytes)) return Ok{};
            record = pending_.data();
        } else {
            record = bytes.data() + pos;
            pos += record_bytes;
        }
        Status accepted = take_record(record);
        pending_.clear();
        if (!accepted) return fail("geometry channel: " + accepted.error());
        ++received_;
    }
    return Ok{};
}

Result<SceneGeometry> GeometryChannelReader::finish() {
    if (failed_) return make_error("geometry channel was already refused");
    failed_ = true;  // either refused now or spent: the geometry moves out
    if (section_ != Section::kDone || !pending_.empty()) {
        const char* what = section_ == Section::kMaterials ? "materials" : "triangles";
        if (expected_ < 0)
            return make_error("geometry channel ended before the count of its " + std::string(what));
        return make_error("geometry channel ended after " + std::to_string(received_) + " of " +
                          std::to_string(expected_) + " " + what);
    }
    return std::move(geometry_);
}

Result<SceneGeometry> decode_geometry_channel(std::span<const uint8_t> bytes,
                                              size_t* degenerate_skipped) {
    GeometryChannelReader reader;
    Status consumed = reader.consume(bytes);
    if (!consumed) return make_error(consumed.error());
    if (degenerate_skipped) *degenerate_skipped = reader.degenerate_skipped();
    return reader.finish();
}

}  // namespace lc

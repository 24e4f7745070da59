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
static_assert(sizeof(fb::SurfaceMaskRecord) == 8);
static_assert(sizeof(fb::MaskedTriangleRecord) == 32);

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

const char* section_name(int section) {
    static const char* const names[] = {"material", "triangle", "mask", "mask word", "masked triangle"};
    return names[section];
}

uint64_t count_limit(int section) {
    static const uint64_t limits[] = {kMaxGeometryMaterials, kMaxGeometryTriangles, kMaxGeometryMasks,
                                      kMaxGeometryMaskWords, kMaxGeometryTriangles};
    return limits[section];
}

void put_masks(std::vector<uint8_t>& out, const SceneGeometry& geometry) {
    put_u32(out, static_cast<uint32_t>(geometry.masks.size()));
    uint64_t words = 0;
    for (const SurfaceMask& m : geometry.masks) {
        append_struct(out, fb::SurfaceMaskRecord(m.width, m.height));
        words += m.keep_bits.size();
    }
    put_u32(out, static_cast<uint32_t>(words));
    for (const SurfaceMask& m : geometry.masks)
        for (uint32_t w : m.keep_bits) put_u32(out, w);
    put_u32(out, static_cast<uint32_t>(geometry.masked_triangles.size()));
    for (const MaskedTriangle& t : geometry.masked_triangles) {
        append_struct(out, fb::MaskedTriangleRecord(t.triangle, t.mask, t.uvs[0].x, t.uvs[0].y, t.uvs[1].x,
                                                    t.uvs[1].y, t.uvs[2].x, t.uvs[2].y));
    }
}

}  // namespace

size_t geometry_mask_record_bytes() { return sizeof(fb::SurfaceMaskRecord); }
size_t geometry_masked_triangle_record_bytes() { return sizeof(fb::MaskedTriangleRecord); }

uint64_t max_geometry_channel_bytes() {
    return geometry_channel_bytes(kMaxGeometryMaterials, kMaxGeometryTriangles) + 3 * kCountBytes +
           uint64_t{kMaxGeometryMasks} * sizeof(fb::SurfaceMaskRecord) +
           uint64_t{kMaxGeometryMaskWords} * sizeof(uint32_t) +
           uint64_t{kMaxGeometryTriangles} * sizeof(fb::MaskedTriangleRecord);
}

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
    // A scene without masks sends what it always did.
    if (!geometry.masks.empty() || !geometry.masked_triangles.empty()) put_masks(out, geometry);
    return out;
}

void GeometryChannelReader::next_section() {
    section_ = Section(int(section_) + 1);
    expected_ = -1;
    received_ = 0;
}

size_t GeometryChannelReader::record_bytes() const {
    switch (section_) {
        case Section::kMaterials: return sizeof(fb::SurfaceMaterialRecord);
        case Section::kTriangles: return sizeof(fb::SurfaceTriangleRecord);
        case Section::kMasks: return sizeof(fb::SurfaceMaskRecord);
        case Section::kMaskWords: return sizeof(uint32_t);
        default: return sizeof(fb::MaskedTriangleRecord);
    }
}

Status GeometryChannelReader::start_section(int32_t count) {
    const int section = int(section_);
    if (count < 0 || uint64_t(count) > count_limit(section))
        return make_error(count_error(count, uint32_t(count_limit(section)), section_name(section)));
    if (section_ == Section::kMaskWords && uint64_t(count) != mask_words_)
        return make_error("mask word count " + std::to_string(count) + " is not the masks' " +
                          std::to_string(mask_words_) + " words");
    if (section_ == Section::kMaskedTriangles && size_t(count) > triangles_sent_)
        return make_error("masked triangle count " + std::to_string(count) + " exceeds the " +
                          std::to_string(triangles_sent_) + " triangles");
    const size_t up_front = std::min<size_t>(size_t(count), kMaxUpFrontRecords);
    if (section_ == Section::kMaterials) geometry_.materials.reserve(up_front);
    if (section_ == Section::kTriangles) geometry_.triangles.reserve(up_front);
    if (section_ == Section::kMaskedTriangles) geometry_.masked_triangles.reserve(up_front);
    expected_ = count;
    return Ok{};
}

Status GeometryChannelReader::take_triangle(const uint8_t* record) {
    Result<SurfaceTriangle> t = from_record(read_struct<fb::SurfaceTriangleRecord>(record), received_,
                                            geometry_.materials.size());
    if (!t) return make_error(t.error());
    if (is_degenerate(*t)) {
        ++degenerate_;
        skipped_.push_back(uint32_t(triangles_sent_));
    } else {
        geometry_.triangles.push_back(*t);
    }
    ++triangles_sent_;
    return Ok{};
}

Status GeometryChannelReader::take_mask(const uint8_t* record) {
    const auto r = read_struct<fb::SurfaceMaskRecord>(record);
    const uint64_t texels = uint64_t(r.width()) * r.height();
    const std::string who = "mask " + std::to_string(received_) + ": ";
    if (texels == 0 || texels > kMaxGeometryMaskTexels)
        return make_error(who + std::to_string(r.width()) + " x " + std::to_string(r.height()) +
                          " texels is not within 1 and " + std::to_string(kMaxGeometryMaskTexels));
    mask_words_ += surface_mask_words(r.width(), r.height());
    if (mask_words_ > kMaxGeometryMaskWords)
        return make_error(who + "the masks exceed " + std::to_string(kMaxGeometryMaskWords) + " keep words");
    geometry_.masks.push_back(SurfaceMask{r.width(), r.height(), {}});
    return Ok{};
}

void GeometryChannelReader::take_mask_word(uint32_t word) {
    // The count matched the masks' words, so a mask with room is always there.
    while (geometry_.masks[filling_mask_].keep_bits.size() ==
           surface_mask_words(geometry_.masks[filling_mask_].width, geometry_.masks[filling_mask_].height))
        ++filling_mask_;
    geometry_.masks[filling_mask_].keep_bits.push_back(word);
}

Status GeometryChannelReader::take_masked_triangle(const uint8_t* record) {
    const auto r = read_struct<fb::MaskedTriangleRecord>(record);
    const std::string who = "masked triangle " + std::to_string(received_) + ": ";
    if (int64_t(r.triangle()) <= last_masked_ || r.triangle() >= triangles_sent_)
        return make_error(who + "triangle " + std::to_string(r.triangle()) + " is out of order or range (" +
                          std::to_string(triangles_sent_) + " triangles)");
    if (r.mask() >= geometry_.masks.size())
        return make_error(who + "mask " + std::to_string(r.mask()) + " is out of range (" +
                          std::to_string(geometry_.masks.size()) + " masks)");
    const float uv[6] = {r.u0(), r.v0(), r.u1(), r.v1(), r.u2(), r.v2()};
    for (float c : uv)
        if (!std::isfinite(c)) return make_error(who + "texture coordinate " + number(c) + " is not finite");
    last_masked_ = r.triangle();
    // Its triangle was degenerate and left out: nothing to mask.
    const auto skipped = std::lower_bound(skipped_.begin(), skipped_.end(), r.triangle());
    if (skipped != skipped_.end() && *skipped == r.triangle()) return Ok{};
    MaskedTriangle t;
    t.triangle = r.triangle() - uint32_t(skipped - skipped_.begin());
    t.mask = r.mask();
    for (int k = 0; k < 3; ++k) t.uvs[k] = glm::vec2(uv[2 * k], uv[2 * k + 1]);
    geometry_.masked_triangles.push_back(t);
    return Ok{};
}

Status GeometryChannelReader::take_record(const uint8_t* record) {
    switch (section_) {
        case Section::kMaterials: {
            Result<SurfaceMaterial> m = from_record(read_struct<fb::SurfaceMaterialRecord>(record), received_);
            if (!m) return make_error(m.error());
            geometry_.materials.push_back(*m);
            return Ok{};
        }
        case Section::kTriangles: return take_triangle(record);
        case Section::kMasks: return take_mask(record);
        case Section::kMaskWords: take_mask_word(uint32_t(get_i32(record))); return Ok{};
        default: return take_masked_triangle(record);
    }
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
                        " bytes after its masked triangles");
        }
        if (expected_ < 0) {
            if (!fill_pending(kCountBytes)) return Ok{};
            const int32_t count = get_i32(pending_.data());
            pending_.clear();
            Status started = start_section(count);
            if (!started) return fail("geometry channel: " + started.error());
            continue;
        }
        if (expected_ == int64_t(received_)) {
            next_section();
            continue;
        }
        const size_t size = record_bytes();
        const uint8_t* record = nullptr;
        if (!pending_.empty() || bytes.size() - pos < size) {
            if (!fill_pending(size)) return Ok{};
            record = pending_.data();
        } else {
            record = bytes.data() + pos;
            pos += size;
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
    // The mask sections are optional: a channel may end where they would start.
    const bool without_masks = section_ == Section::kMasks && expected_ < 0;
    if ((section_ != Section::kDone && !without_masks) || !pending_.empty()) {
        const std::string what = std::string(section_name(int(std::min(section_, Section::kMaskedTriangles)))) + "s";
        if (expected_ < 0) return make_error("geometry channel ended before the count of its " + what);
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

#include "editor_client/scene/inputs/scene_guid.h"

#include <bit>
#include <cstring>
#include <string_view>
#include <vector>

namespace lc::client {
namespace {

constexpr uint64_t kFnvOffset = 0xcbf29ce484222325ull;
constexpr uint64_t kFnvPrime = 0x100000001b3ull;

// Little-endian serialisation, so the GUID does not depend on the host.
class ByteWriter {
public:
    void u8(uint8_t v) { bytes_.push_back(v); }
    void u32(uint32_t v) {
        for (int i = 0; i < 4; ++i) bytes_.push_back(static_cast<uint8_t>(v >> (8 * i)));
    }
    void u64(uint64_t v) {
        for (int i = 0; i < 8; ++i) bytes_.push_back(static_cast<uint8_t>(v >> (8 * i)));
    }
    // -0 and +0 describe the same scene: hash them alike.
    void f32(float v) { u32(std::bit_cast<uint32_t>(v == 0.0f ? 0.0f : v)); }
    void vec3(const glm::vec3& v) {
        f32(v.x);
        f32(v.y);
        f32(v.z);
    }
    void text(std::string_view s) {
        u32(static_cast<uint32_t>(s.size()));
        for (char c : s) u8(static_cast<uint8_t>(c));
    }
    const std::vector<uint8_t>& bytes() const { return bytes_; }

private:
    std::vector<uint8_t> bytes_;
};

void fnv_bytes(uint64_t& h, const void* data, size_t size) {
    const auto* p = static_cast<const uint8_t*>(data);
    for (size_t i = 0; i < size; ++i) {
        h ^= p[i];
        h *= kFnvPrime;
    }
}

void fnv_u32(uint64_t& h, uint32_t v) {
    uint8_t le[4] = {static_cast<uint8_t>(v), static_cast<uint8_t>(v >> 8),
                     static_cast<uint8_t>(v >> 16), static_cast<uint8_t>(v >> 24)};
    fnv_bytes(h, le, sizeof le);
}

void fnv_f32(uint64_t& h, float v) {
    fnv_u32(h, std::bit_cast<uint32_t>(v == 0.0f ? 0.0f : v));
}

}  // namespace

uint64_t geometry_hash(const Scene& scene) {
    uint64_t h = kFnvOffset;
    fnv_u32(h, static_cast<uint32_t>(scene.meshes.size()));
    for (const Mesh& mesh : scene.meshes) {
        fnv_u32(h, static_cast<uint32_t>(mesh.positions.size()));
        for (const glm::vec3& p : mesh.positions) {
            fnv_f32(h, p.x);
            fnv_f32(h, p.y);
            fnv_f32(h, p.z);
        }
        fnv_u32(h, static_cast<uint32_t>(mesh.indices.size()));
        for (uint32_t index : mesh.indices) fnv_u32(h, index);
    }
    return h;
}

Guid compute_scene_guid(const Scene& scene) {
    ByteWriter w;
    w.text("lightcuts-scene-v1");
    w.u32(static_cast<uint32_t>(scene.lights.size()));
    for (const SceneLight& light : scene.lights) {
        w.u32(light.guid.a);
        w.u32(light.guid.b);
        w.u32(light.guid.c);
        w.u32(light.guid.d);
        w.u8(static_cast<uint8_t>(light.type));
        w.vec3(light.position);
        w.vec3(light.direction);
        w.vec3(light.color);
        w.f32(light.intensity);
        w.f32(light.range);
        w.f32(light.inner_cone_angle);
        w.f32(light.outer_cone_angle);
        w.u8(light.classic ? 1 : 0);
    }
    w.u64(geometry_hash(scene));
    return Guid::from_bytes(w.bytes());
}

}  // namespace lc::client

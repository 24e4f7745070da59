#pragma once
// What the channel payload codecs (channel_records.cpp, geometry_channel.cpp)
// share: FlatBuffers structs as their own little-endian wire layout, the
// count prefix, and the numbers their error messages quote. Internal to
// protocol/: it includes the generated code, which only those files see.
#include <glm/vec3.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "lightcuts/guid.h"
#include "lightcuts_generated.h"

namespace lc::records {

template <typename Struct>
void append_struct(std::vector<uint8_t>& out, const Struct& s) {
    const auto* bytes = reinterpret_cast<const uint8_t*>(&s);
    out.insert(out.end(), bytes, bytes + sizeof(Struct));
}
// Returns the byte after the struct.
template <typename Struct>
uint8_t* write_struct(uint8_t* out, const Struct& s) {
    std::memcpy(out, &s, sizeof(Struct));
    return out + sizeof(Struct);
}
template <typename Struct>
Struct read_struct(const uint8_t* p) {
    Struct s;
    std::memcpy(static_cast<void*>(&s), p, sizeof(Struct));
    return s;
}

inline void put_u32(std::vector<uint8_t>& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}
inline int32_t get_i32(const uint8_t* p) {
    const uint32_t u = static_cast<uint32_t>(p[0]) | (static_cast<uint32_t>(p[1]) << 8) |
                       (static_cast<uint32_t>(p[2]) << 16) | (static_cast<uint32_t>(p[3]) << 24);
    return static_cast<int32_t>(u);
}

inline fb::Guid to_fb(const Guid& g) { return fb::Guid(g.a, g.b, g.c, g.d); }
inline Guid from_fb(const fb::Guid& g) { return Guid{g.a(), g.b(), g.c(), g.d()}; }
inline fb::Vec3 to_fb(const glm::vec3& v) { return fb::Vec3(v.x, v.y, v.z); }
inline glm::vec3 from_fb(const fb::Vec3& v) { return {v.x(), v.y(), v.z()}; }

inline bool finite3(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}
inline std::string number(double v) {
    char text[64];
    std::snprintf(text, sizeof(text), "%g", v);
    return text;
}
inline std::string vec_text(const glm::vec3& v) {
    return "(" + number(v.x) + ", " + number(v.y) + ", " + number(v.z) + ")";
}

}  // namespace lc::records

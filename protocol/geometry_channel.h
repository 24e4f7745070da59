#pragma once
// The geometry channel, SCENEFORMATVERSION.SCENEGUID.geom (docs/PROTOCOL.md
// §5): the scene's surfaces as the server's area-light sampler and ray caster
// read them. Two count-prefixed sections, materials then triangles:
//   int32 M, M x SurfaceMaterialRecord (32 bytes),
//   int32 T, T x SurfaceTriangleRecord (76 bytes).
// The reader validates each record as it arrives (finite values, ranges,
// material indices) and skips degenerate triangles, counting them.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "lightcuts/result.h"
#include "lightcuts/scene_geometry.h"

namespace lc {

// Size limits (documented in docs/PROTOCOL.md).
inline constexpr uint32_t kMaxGeometryMaterials = 1u << 24;  // 16,777,216: one per textured triangle
inline constexpr uint32_t kMaxGeometryTriangles = 1u << 24;  // 16,777,216

size_t geometry_material_record_bytes();
size_t geometry_triangle_record_bytes();
// Bytes of a channel with this many materials and triangles.
uint64_t geometry_channel_bytes(uint64_t materials, uint64_t triangles);

std::vector<uint8_t> encode_geometry_channel(const SceneGeometry& geometry);

class GeometryChannelReader {
public:
    // Pushes channel bytes; fails on a bad count or record, naming it.
    Status consume(std::span<const uint8_t> bytes);
    // Succeeds only when both sections arrived whole and nothing more.
    Result<SceneGeometry> finish();
    // Triangles of zero or non-finite area, left out of the geometry.
    size_t degenerate_skipped() const { return degenerate_; }

private:
    enum class Section { kMaterials, kTriangles, kDone };
    Status take_record(const uint8_t* record);
    void next_section();

    Section section_ = Section::kMaterials;
    std::vector<uint8_t> pending_;
    int64_t expected_ = -1;  // records announced in the current section; -1: count not read yet
    size_t received_ = 0;    // records of the current section so far
    SceneGeometry geometry_;
    size_t degenerate_ = 0;
    bool failed_ = false;
};

Result<SceneGeometry> decode_geometry_channel(std::span<const uint8_t> bytes,
                                              size_t* degenerate_skipped = nullptr);

}  // namespace lc

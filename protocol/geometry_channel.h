#pragma once
// The geometry channel, SCENEFORMATVERSION.SCENEGUID.geom (docs/PROTOCOL.md
// §5): the scene's surfaces as the server's area-light sampler and ray caster
// read them. Count-prefixed sections, materials then triangles:
//   int32 M, M x SurfaceMaterialRecord (32 bytes),
//   int32 T, T x SurfaceTriangleRecord (76 bytes),
// and, only when the scene has alpha-masked surfaces, three more:
//   int32 K, K x SurfaceMaskRecord (8 bytes),
//   int32 W, W x uint32 keep words (W: the masks' words, exactly),
//   int32 Q, Q x MaskedTriangleRecord (32 bytes).
// The reader validates each record as it arrives (finite values, ranges,
// material and mask indices) and skips degenerate triangles, counting them.
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
inline constexpr uint32_t kMaxGeometryMasks = 1u << 16;          // 65,536
inline constexpr uint64_t kMaxGeometryMaskTexels = 1ull << 26;   // per mask: 8192 x 8192
inline constexpr uint32_t kMaxGeometryMaskWords = 1u << 26;      // all masks: 256 MiB of keep bits

size_t geometry_material_record_bytes();
size_t geometry_triangle_record_bytes();
size_t geometry_mask_record_bytes();
size_t geometry_masked_triangle_record_bytes();
// Bytes of a channel with this many materials and triangles and no masks.
uint64_t geometry_channel_bytes(uint64_t materials, uint64_t triangles);
// The most bytes a channel within every limit above can hold.
uint64_t max_geometry_channel_bytes();

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
    enum class Section { kMaterials, kTriangles, kMasks, kMaskWords, kMaskedTriangles, kDone };
    Status take_record(const uint8_t* record);
    Status take_triangle(const uint8_t* record);
    Status take_mask(const uint8_t* record);
    void take_mask_word(uint32_t word);
    Status take_masked_triangle(const uint8_t* record);
    Status start_section(int32_t count);
    size_t record_bytes() const;
    void next_section();

    Section section_ = Section::kMaterials;
    std::vector<uint8_t> pending_;
    int64_t expected_ = -1;  // records announced in the current section; -1: count not read yet
    size_t received_ = 0;    // records of the current section so far
    SceneGeometry geometry_;
    size_t degenerate_ = 0;
    size_t triangles_sent_ = 0;         // triangle records, degenerate ones too
    std::vector<uint32_t> skipped_;     // the degenerate ones' indices, increasing
    uint64_t mask_words_ = 0;           // the masks' keep words, summed
    size_t filling_mask_ = 0;           // the mask the next keep word belongs to
    int64_t last_masked_ = -1;          // the last masked triangle's index
    bool failed_ = false;
};

Result<SceneGeometry> decode_geometry_channel(std::span<const uint8_t> bytes,
                                              size_t* degenerate_skipped = nullptr);

}  // namespace lc

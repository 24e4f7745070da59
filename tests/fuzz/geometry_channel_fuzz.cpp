// Geometry channel reader (untrusted triangles and materials from a client):
// any payload, pushed whole or in pieces, gives the same verdict, the same
// surfaces and the same count of skipped degenerate triangles; what decodes
// is finite and its material indices are in range; its masks hold all their
// keep words and the masked triangles name kept triangles and masks in order.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "fuzz_check.h"
#include "protocol/geometry_channel.h"

namespace {

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using lc::fuzz::check;
    if (size == 0) return 0;
    const size_t stride = size_t(data[0]) * 7 + 1;  // the first byte picks the piece size
    const std::span<const uint8_t> input(data + 1, size - 1);

    size_t whole_degenerate = 0;
    lc::Result<lc::SceneGeometry> whole = lc::decode_geometry_channel(input, &whole_degenerate);
    lc::GeometryChannelReader reader;
    bool pieces_ok = true;
    for (size_t at = 0; at < input.size() && pieces_ok; at += stride) {
        pieces_ok = reader.consume(input.subspan(at, std::min(stride, input.size() - at))).ok();
    }
    const size_t pieces_degenerate = reader.degenerate_skipped();
    lc::Result<lc::SceneGeometry> pieces =
        pieces_ok ? reader.finish() : lc::Result<lc::SceneGeometry>(lc::make_error("refused"));
    check(whole.ok() == pieces.ok(), "the verdict does not depend on how the bytes arrive");
    if (!whole) return 0;

    check(lc::encode_geometry_channel(*whole) == lc::encode_geometry_channel(*pieces),
          "whole and pieces give the same surfaces");
    check(whole_degenerate == pieces_degenerate, "whole and pieces skip the same triangles");
    for (const lc::SurfaceMaterial& m : whole->materials) {
        check(finite(m.base_color) && finite(m.emission), "materials are finite");
        check(m.emission.x >= 0.0f && m.emission.y >= 0.0f && m.emission.z >= 0.0f,
              "emission is never negative");
    }
    for (const lc::SurfaceTriangle& t : whole->triangles) {
        check(t.material < whole->materials.size(), "every triangle's material exists");
        check(!lc::is_degenerate(t), "degenerate triangles are skipped");
        for (int k = 0; k < 3; ++k) check(finite(t.positions[k]) && finite(t.normals[k]), "triangles are finite");
    }
    for (const lc::SurfaceMask& m : whole->masks)
        check(m.keep_bits.size() == lc::surface_mask_words(m.width, m.height), "every mask has all its keep words");
    int64_t last = -1;
    for (const lc::MaskedTriangle& t : whole->masked_triangles) {
        check(int64_t(t.triangle) > last && t.triangle < whole->triangles.size(),
              "masked triangles are increasing kept triangles");
        check(t.mask < whole->masks.size(), "every masked triangle's mask exists");
        for (const glm::vec2& uv : t.uvs) check(std::isfinite(uv.x) && std::isfinite(uv.y), "uvs are finite");
        last = t.triangle;
    }
    return 0;
}

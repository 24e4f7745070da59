#include "lightmass_server/raycast/ray_caster.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>
#include <string>

namespace lc {

namespace {

// Embree reports errors through a callback; the build collects the first.
void record_error(void* user, RTCError code, const char* message) {
    auto* first = static_cast<std::string*>(user);
    if (first->empty()) {
        *first = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
    }
}

RTCRay make_ray(glm::vec3 origin, glm::vec3 direction, float t_min, float t_max) {
    RTCRay ray{};
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = direction.x;
    ray.dir_y = direction.y;
    ray.dir_z = direction.z;
    ray.tnear = t_min;
    ray.tfar = t_max;
    ray.mask = std::numeric_limits<unsigned>::max();
    ray.flags = 0;
    ray.time = 0.0f;
    return ray;
}

}  // namespace

// What the masked geometry's filter reads: per Embree primitive, its mask
// and corner texture coordinates.
struct RayCaster::MaskedPrimitives {
    std::vector<SurfaceMask> masks;
    std::vector<MaskedTriangle> primitives;  // .triangle unused here
};

struct RayCaster::Embree {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::string error;
    MaskedPrimitives masked;  // here, so its address survives moves of the caster

    ~Embree() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

namespace {

constexpr unsigned kOpaqueGeometry = 0;
constexpr unsigned kMaskedGeometry = 1;

// Embree's hit filter (intersections and occlusion alike): a hit on a texel
// the mask cuts out is no hit, and the ray goes on.
template <typename Masked>
void pass_cut_outs(const RTCFilterFunctionNArguments* args) {
    const auto* masked = static_cast<const Masked*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] == 0) continue;
        const MaskedTriangle& t = masked->primitives[RTCHitN_primID(args->hit, args->N, i)];
        const glm::vec2 uv = masked_uv(t, RTCHitN_u(args->hit, args->N, i), RTCHitN_v(args->hit, args->N, i));
        if (!surface_mask_keeps(masked->masks[t.mask], uv)) args->valid[i] = 0;
    }
}

}  // namespace

Status RayCaster::attach(const SceneGeometry& geometry, const std::vector<uint32_t>& triangles, bool masked) {
    Embree& e = *embree_;
    const size_t count = triangles.size();
    if (count == 0) return Ok{};
    RTCGeometry mesh = rtcNewGeometry(e.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        mesh, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * count));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        mesh, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), count));
    if (!vertices || !indices) {
        rtcReleaseGeometry(mesh);
        return make_error("Embree could not allocate " + std::to_string(count) + " triangles: " + e.error);
    }
    for (size_t p = 0; p < count; ++p) {
        const SurfaceTriangle& t = geometry.triangles[triangles[p]];
        for (int k = 0; k < 3; ++k) {
            vertices[9 * p + 3 * k + 0] = t.positions[k].x;
            vertices[9 * p + 3 * k + 1] = t.positions[k].y;
            vertices[9 * p + 3 * k + 2] = t.positions[k].z;
            indices[3 * p + k] = unsigned(3 * p + k);
        }
    }
    if (masked) {
        rtcSetGeometryUserData(mesh, &e.masked);
        rtcSetGeometryIntersectFilterFunction(mesh, pass_cut_outs<MaskedPrimitives>);
        rtcSetGeometryOccludedFilterFunction(mesh, pass_cut_outs<MaskedPrimitives>);
    }
    rtcCommitGeometry(mesh);
    rtcAttachGeometryByID(e.scene, mesh, masked ? kMaskedGeometry : kOpaqueGeometry);
    rtcReleaseGeometry(mesh);
    return Ok{};
}

Result<RayCaster> RayCaster::build(const SceneGeometry& geometry, int threads) {
    RayCaster caster;
    caster.embree_ = std::make_unique<Embree>();
    Embree& e = *caster.embree_;
    std::string config = threads > 0 ? "threads=" + std::to_string(threads) : std::string();
    e.device = rtcNewDevice(config.empty() ? nullptr : config.c_str());
    if (!e.device) return Error{"cannot create the Embree device (error " +
                                std::to_string(int(rtcGetDeviceError(nullptr))) + ")"};
    rtcSetDeviceErrorFunction(e.device, record_error, &e.error);

    // The channel's reader checked the masked triangles: increasing, in range.
    e.masked.masks = geometry.masks;
    auto next_masked = geometry.masked_triangles.begin();
    for (uint32_t i = 0; i < geometry.triangles.size(); ++i) {
        while (next_masked != geometry.masked_triangles.end() && next_masked->triangle < i) ++next_masked;
        const bool masked = next_masked != geometry.masked_triangles.end() && next_masked->triangle == i &&
                            next_masked->mask < geometry.masks.size();
        if (is_degenerate(geometry.triangles[i])) {
            ++caster.skipped_degenerate_;
        } else if (masked) {
            caster.masked_to_triangle_.push_back(i);
            e.masked.primitives.push_back(*next_masked);
        } else {
            caster.primitive_to_triangle_.push_back(i);
        }
    }

    // Robust traversal: rays that graze shared edges of a closed room must
    // not slip through the cracks the fast path leaves.
    e.scene = rtcNewScene(e.device);
    rtcSetSceneFlags(e.scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(e.scene, RTC_BUILD_QUALITY_HIGH);
    Status opaque = caster.attach(geometry, caster.primitive_to_triangle_, false);
    if (!opaque) return make_error(opaque.error());
    Status masked = caster.attach(geometry, caster.masked_to_triangle_, true);
    if (!masked) return make_error(masked.error());
    rtcCommitScene(e.scene);
    if (!e.error.empty()) return Error{"building the ray-casting scene failed: " + e.error};
    return caster;
}

std::optional<uint32_t> RayCaster::triangle_of(unsigned geometry_id, unsigned primitive) const {
    const std::vector<uint32_t>& map = geometry_id == kMaskedGeometry ? masked_to_triangle_ : primitive_to_triangle_;
    if (primitive >= map.size()) return std::nullopt;
    return map[primitive];
}

RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;
RayCaster::~RayCaster() = default;

std::optional<RayHit> RayCaster::intersect(glm::vec3 origin, glm::vec3 direction, float t_min,
                                           float t_max) const {
    if (triangle_count() == 0 || !(t_max > t_min)) return std::nullopt;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit query{};
    query.ray = make_ray(origin, direction, t_min, t_max);
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree_->scene, &context, &query);
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    const std::optional<uint32_t> triangle = triangle_of(query.hit.geomID, query.hit.primID);
    if (!triangle) return std::nullopt;
    return RayHit{query.ray.tfar, *triangle, query.hit.u, query.hit.v};
}

bool RayCaster::occluded(glm::vec3 origin, glm::vec3 direction, float t_min, float t_max) const {
    if (triangle_count() == 0 || !(t_max > t_min)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = make_ray(origin, direction, t_min, t_max);
    rtcOccluded1(embree_->scene, &context, &ray);
    // Embree marks an occluded ray by setting tfar to -inf.
    return ray.tfar < 0.0f;
}

}  // namespace lc

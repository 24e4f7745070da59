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

struct RayCaster::Embree {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::string error;

    ~Embree() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

Result<RayCaster> RayCaster::build(const SceneGeometry& geometry, int threads) {
    RayCaster caster;
    caster.embree_ = std::make_unique<Embree>();
    Embree& e = *caster.embree_;
    std::string config = threads > 0 ? "threads=" + std::to_string(threads) : std::string();
    e.device = rtcNewDevice(config.empty() ? nullptr : config.c_str());
    if (!e.device) return Error{"cannot create the Embree device (error " +
                                std::to_string(int(rtcGetDeviceError(nullptr))) + ")"};
    rtcSetDeviceErrorFunction(e.device, record_error, &e.error);

    for (uint32_t i = 0; i < geometry.triangles.size(); ++i) {
        if (is_degenerate(geometry.triangles[i])) {
            ++caster.skipped_degenerate_;
        } else {
            caster.primitive_to_triangle_.push_back(i);
        }
    }

    // Robust traversal: rays that graze shared edges of a closed room must
    // not slip through the cracks the fast path leaves.
    e.scene = rtcNewScene(e.device);
    rtcSetSceneFlags(e.scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(e.scene, RTC_BUILD_QUALITY_HIGH);
    const size_t count = caster.primitive_to_triangle_.size();
    if (count > 0) {
        RTCGeometry mesh = rtcNewGeometry(e.device, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            mesh, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * count));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            mesh, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), count));
        if (!vertices || !indices) {
            rtcReleaseGeometry(mesh);
            return Error{"Embree could not allocate " + std::to_string(count) +
                         " triangles: " + e.error};
        }
        for (size_t p = 0; p < count; ++p) {
            const SurfaceTriangle& t = geometry.triangles[caster.primitive_to_triangle_[p]];
            for (int k = 0; k < 3; ++k) {
                vertices[9 * p + 3 * k + 0] = t.positions[k].x;
                vertices[9 * p + 3 * k + 1] = t.positions[k].y;
                vertices[9 * p + 3 * k + 2] = t.positions[k].z;
                indices[3 * p + k] = unsigned(3 * p + k);
            }
        }
        rtcCommitGeometry(mesh);
        rtcAttachGeometry(e.scene, mesh);
        rtcReleaseGeometry(mesh);
    }
    rtcCommitScene(e.scene);
    if (!e.error.empty()) return Error{"building the ray-casting scene failed: " + e.error};
    return caster;
}

RayCaster::RayCaster(RayCaster&&) noexcept = default;
RayCaster& RayCaster::operator=(RayCaster&&) noexcept = default;
RayCaster::~RayCaster() = default;

std::optional<RayHit> RayCaster::intersect(glm::vec3 origin, glm::vec3 direction, float t_min,
                                           float t_max) const {
    if (primitive_to_triangle_.empty() || !(t_max > t_min)) return std::nullopt;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit query{};
    query.ray = make_ray(origin, direction, t_min, t_max);
    query.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    query.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(embree_->scene, &context, &query);
    if (query.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
    return RayHit{query.ray.tfar, primitive_to_triangle_[query.hit.primID], query.hit.u,
                  query.hit.v};
}

bool RayCaster::occluded(glm::vec3 origin, glm::vec3 direction, float t_min, float t_max) const {
    if (primitive_to_triangle_.empty() || !(t_max > t_min)) return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = make_ray(origin, direction, t_min, t_max);
    rtcOccluded1(embree_->scene, &context, &ray);
    // Embree marks an occluded ray by setting tfar to -inf.
    return ray.tfar < 0.0f;
}

}  // namespace lc

// std430 mirrors of editor_client/render/gpu_layout.h, field for field.
// tests/gpu_layout_test.cpp checks the C++ side; keep both in step.
#ifndef LC_GPU_LAYOUT_GLSL
#define LC_GPU_LAYOUT_GLSL

const uint kLightPoint = 0u;
const uint kLightSpot = 1u;
const uint kLightDirectional = 2u;

const int kEndOfWalk = -1;
const uint kNodeMixedTypes = 1u;

struct GpuLight {
    vec3 position;
    float range;
    vec3 direction;
    uint type;
    vec3 intensity;
    float spot_cos_outer;
    float spot_cos_inner;
    float spot_scale;
    uint pad0;
    uint pad1;
};

struct GpuTreeNode {
    GpuLight light;
    int first_child;
    int escape;
    float radius;
    uint flags;
};

struct GpuNodeBounds {
    vec3 bbox_min;
    float cone_cos;
    vec3 bbox_max;
    float pad0;
    vec3 cone_axis;
    float pad1;
};

// GpuWalkState: one pixel's walk search between passes.
const uint kWalkDone = 1u;
const uint kWalkRuleMet = 2u;
const uint kWalkBisecting = 4u;
const uint kWalkLoopStop = 8u;
const uint kWalkStorePending = 16u;  // done where the loop limit fired: stored next dispatch
const uint kWalkBisectionsShift = 8u;

struct GpuWalkState {
    vec3 radiance;
    uint size;
    uint hash;
    float tau;
    float fit_hi;
    float over_lo;
    uint flags;
    uint passes;  // passes completed
    uint pad1;
    uint pad2;
};

// editor_client/render/shadow_bvh.h
const uint kBvhLeafCountBits = 3u;
const uint kBvhLeafCountMask = 7u;

struct GpuBvhNode {
    vec3 bbox_min;
    int escape;
    vec3 bbox_max;
    uint triangles;  // leaf: first << kBvhLeafCountBits | count; inner: 0
};

struct GpuShadowTriangle {
    vec3 v0;
    float pad0;
    vec3 edge1;
    float pad1;
    vec3 edge2;
    float pad2;
};

#endif

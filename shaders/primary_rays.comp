#version 460
// Primary visibility cast as rays (RenderSettings::primary, PrimaryRaysPass):
// the G-buffer gbuffer.vert/frag rasterise, written by a compute pass instead.
// A compute GPU rasterises on few units (an H200 took 6.1 ms for a 1080p
// G-buffer of a few hundred triangles, in proportion to the pixels) while
// every unit can cast rays. Each pixel's eye ray (its centre through the
// raster pass's eye_ray_view_projection, inverted) finds the closest triangle
// in a BVH over every triangle; the hit's barycentrics interpolate the
// vertex normal and COLOR_0 as the rasteriser's perspective-correct
// interpolation does, and its draw's material gives the rest. Textures are
// the raster pass's alone (a scene with any stays on raster).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require

#include "lightcuts/device/bindings.h"
#include "lightcuts/device/gpu_structs.h"
#include "lightcuts/device/spec_constants.h"

layout(local_size_x_id = kSpecWorkgroupX, local_size_y_id = kSpecWorkgroupY) in;

layout(set = 0, binding = kBindPosition, rgba32f) uniform writeonly image2D gbuffer_position;
layout(set = 0, binding = kBindNormal, rgba32f) uniform writeonly image2D gbuffer_normal;
layout(set = 0, binding = kBindAlbedo, rgba32f) uniform writeonly image2D gbuffer_albedo;
layout(set = 0, binding = kBindEmissive, rgba32f) uniform writeonly image2D gbuffer_emissive;
layout(push_constant) uniform FrameConstants { GpuFrameConstants frame; };

layout(std430, set = kPrimarySet, binding = kBindPrimaryNodes) readonly buffer PrimaryNodes {
    GpuBvhNode primary_nodes[];
};
layout(std430, set = kPrimarySet, binding = kBindPrimaryTriangles) readonly buffer PrimaryTriangles {
    GpuShadowTriangle primary_triangles[];
};
layout(std430, set = kPrimarySet, binding = kBindPrimarySources) readonly buffer PrimarySources {
    GpuPrimaryTriangle primary_sources[];
};
layout(std430, set = kPrimarySet, binding = kBindSceneVertices) readonly buffer SceneVertices {
    GpuSceneVertex scene_vertices[];
};
layout(std430, set = kPrimarySet, binding = kBindSurfaceMaterials) readonly buffer SurfaceMaterials {
    GpuSurfaceMaterial surface_materials[];
};
layout(std430, set = kPrimarySet, binding = kBindPrimaryParams) readonly buffer PrimaryParams {
    GpuPrimaryParams primary;
};

const float kNoHit = 3.402823466e38;

// Moller-Trumbore, both faces, the closest hit so far: t in (0, t_best).
// `front`: the ray meets the counter-clockwise side (det > 0).
bool closer_hit(vec3 origin, vec3 direction, float t_best, GpuShadowTriangle tri, out float t,
                out vec2 bary, out bool front) {
    vec3 p = cross(direction, tri.edge2);
    float det = dot(tri.edge1, p);
    t = kNoHit;
    bary = vec2(0.0);
    front = det > 0.0;
    if (det == 0.0) return false;
    float inv_det = 1.0 / det;
    vec3 s = origin - tri.v0;
    float u = dot(s, p) * inv_det;
    vec3 q = cross(s, tri.edge1);
    float v = dot(direction, q) * inv_det;
    t = dot(tri.edge2, q) * inv_det;
    bary = vec2(u, v);
    return u >= 0.0 && v >= 0.0 && u + v <= 1.0 && t > 0.0 && t < t_best;
}

// Slab test: does the ray enter the box before t_best?
bool box_before(vec3 origin, vec3 inv_direction, float t_best, vec3 lo, vec3 hi) {
    vec3 t0 = (lo - origin) * inv_direction;
    vec3 t1 = (hi - origin) * inv_direction;
    vec3 near = min(t0, t1);
    vec3 far = max(t0, t1);
    float enter = max(max(near.x, near.y), max(near.z, 0.0));
    float leave = min(min(far.x, far.y), min(far.z, t_best)) * 1.000001;
    return enter <= leave;
}

struct Hit {
    float t;
    int triangle;  // leaf-order index, -1: none
    vec2 bary;
    bool front;  // the counter-clockwise side
};

// glTF doubleSided false: the back face is not seen (the ray goes on).
bool culled(uint triangle, bool front) {
    return !front && (surface_materials[primary_sources[triangle].draw].flags & kDrawSingleSided) != 0u;
}

// One node of the subgroup's shared walk (shadow_rays.glsl's, for the
// closest hit): every lane reads the same node, the subgroup enters it when
// any lane's ray meets its box before that lane's closest hit.
void primary_walk_step(inout int i, inout Hit hit, vec3 origin, vec3 direction, vec3 inv_direction,
                       bool searching) {
    GpuBvhNode node = primary_nodes[i];
    bool enter = searching && box_before(origin, inv_direction, hit.t, node.bbox_min, node.bbox_max);
    uint count = node.triangles & kBvhLeafCountMask;
    if (count == 0u) {
        i = subgroupAny(enter) ? i + 1 : node.escape;
        return;
    }
    uint first = node.triangles >> kBvhLeafCountBits;
    // A constant trip count (unrolled): no loop budget spent on llvmpipe.
    for (uint k = 0u; k < kBvhMaxLeafSize; ++k) {
        if (k < count && enter) {
            float t;
            vec2 bary;
            bool front;
            if (closer_hit(origin, direction, hit.t, primary_triangles[first + k], t, bary, front) &&
                !culled(first + k, front))
                hit = Hit(t, int(first + k), bary, front);
        }
    }
    i = node.escape;
}

// The closest triangle along the ray. A walk visits each node at most once:
// the pass refuses a BVH of more nodes than the device's loop limit.
Hit closest_hit(vec3 origin, vec3 direction, bool searching) {
    vec3 inv_direction = 1.0 / mix(direction, vec3(1e-30), equal(direction, vec3(0.0)));
    Hit hit = Hit(kNoHit, -1, vec2(0.0), true);
    int i = primary.node_count == 0u ? kEndOfWalk : 0;
    // Every node is visited at most once; the bound only guards a corrupt upload.
    for (uint step = 0u; i != kEndOfWalk && step < primary.node_count; ++step)
        primary_walk_step(i, hit, origin, direction, inv_direction, searching);
    return hit;
}

vec3 vertex_normal(uint v) {
    GpuSceneVertex vertex = scene_vertices[v];
    return vec3(vertex.position_normal_x.w, vertex.normal_yz_uv.xy);
}

vec4 vertex_color(uint v) { return scene_vertices[v].color; }

// gbuffer.frag's outputs at the hit.
void store_surface(ivec2 pixel, Hit hit, vec3 position) {
    GpuShadowTriangle tri = primary_triangles[hit.triangle];
    GpuPrimaryTriangle source = primary_sources[hit.triangle];
    vec3 w = vec3(1.0 - hit.bary.x - hit.bary.y, hit.bary.x, hit.bary.y);
    vec3 n = vertex_normal(source.v0) * w.x + vertex_normal(source.v1) * w.y + vertex_normal(source.v2) * w.z;
    bool has_normal = dot(n, n) > 1e-24;
    // No vertex normal: the triangle's own (the raster pass takes it from derivatives).
    if (!has_normal) n = cross(tri.edge1, tri.edge2);
    float len = length(n);
    n = len > 0.0 ? n / len : vec3(0.0, 1.0, 0.0);
    // As gbuffer.frag: a back face's normal reversed; a face normal faces the camera.
    bool back = has_normal ? !hit.front : dot(n, primary.eye - position) < 0.0;
    if (back) n = -n;
    GpuSurfaceMaterial material = surface_materials[source.draw];
    vec4 base = material.base_color_factor;
    if ((material.flags & kDrawVertexColors) != 0u)
        base *= vertex_color(source.v0) * w.x + vertex_color(source.v1) * w.y + vertex_color(source.v2) * w.z;
    imageStore(gbuffer_position, pixel, vec4(position, 1.0));
    imageStore(gbuffer_normal, pixel, vec4(n, material.roughness));
    imageStore(gbuffer_albedo, pixel, vec4(base.rgb, material.emissive_metallic.a));
    imageStore(gbuffer_emissive, pixel, vec4(material.emissive_metallic.rgb, 1.0));
}

void main() {
    ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
    bool inside = pixel.x < int(frame.width) && pixel.y < int(frame.height);
    // The pixel centre in clip space on the far plane: the ray from the eye through it.
    vec2 ndc = (vec2(pixel) + 0.5) / vec2(frame.width, frame.height) * 2.0 - 1.0;
    vec4 far = primary.inverse_view_proj * vec4(ndc, 1.0, 1.0);
    vec3 origin = primary.eye;
    vec3 direction = far.xyz / far.w - origin;
    // Lanes off the image walk with the others (the walk is the subgroup's).
    Hit hit = closest_hit(origin, direction, inside);
    if (!inside) return;
    if (hit.triangle < 0) {
        // Background: w = 0, as the raster pass's clear.
        imageStore(gbuffer_position, pixel, vec4(0.0));
        imageStore(gbuffer_normal, pixel, vec4(0.0));
        imageStore(gbuffer_albedo, pixel, vec4(0.0));
        imageStore(gbuffer_emissive, pixel, vec4(0.0));
        return;
    }
    store_surface(pixel, hit, origin + hit.t * direction);
}

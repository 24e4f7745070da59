// Upper bounds on what a light-tree cluster can contribute at a point, for the
// bound criterion (paper Sec. 4.1). A float mirror of geometric_bound() in
// editor_client/render/cpu_evaluator.cpp: same cases, same order.
#ifndef LC_CLUSTER_BOUNDS_GLSL
#define LC_CLUSTER_BOUNDS_GLSL

#include "common_lighting.glsl"
#include "frame_bindings.glsl"
#include "material_model.glsl"

// Upper bound of cos(angle(axis, v)) over every v in the box [lo, hi] (paper
// Eq. 4): rotate the box into a frame whose z is `axis` and take the rotated
// box's bounding box (centre rotated, half extents through |R|: the same box
// as the eight rotated corners', at a third of the work), then bound
// v_z / |v| from the largest v_z and the smallest (or largest) lateral extent.
float max_cos_to_box(vec3 axis, vec3 lo, vec3 hi) {
    // Orthonormal frame (t, s, axis), Duff et al.'s branchless construction.
    float sign_z = axis.z < 0.0 ? -1.0 : 1.0;
    float a = -1.0 / (sign_z + axis.z);
    float b = axis.x * axis.y * a;
    vec3 t = vec3(1.0 + sign_z * axis.x * axis.x * a, sign_z * b, -sign_z * axis.x);
    vec3 s = vec3(b, sign_z + axis.y * axis.y * a, -axis.y);
    vec3 center = 0.5 * (lo + hi);
    vec3 half_extent = 0.5 * (hi - lo);
    vec3 local = vec3(dot(center, t), dot(center, s), dot(center, axis));
    vec3 reach = vec3(dot(half_extent, abs(t)), dot(half_extent, abs(s)), dot(half_extent, abs(axis)));
    // Rounding must not shrink the box: widen it by a few float ulps of the
    // largest terms the dot products summed (a grazing corner cancels them).
    vec3 magnitude = vec3(dot(abs(center), abs(t)), dot(abs(center), abs(s)), dot(abs(center), abs(axis)));
    reach += (magnitude + reach) * 1e-6;
    vec3 llo = local - reach;
    vec3 lhi = local + reach;
    float z_max = lhi.z;
    vec2 lat_lo = llo.xy;
    vec2 lat_hi = lhi.xy;
    if (z_max >= 0.0) {
        // Smallest squared lateral extent: 0 when the interval straddles 0.
        vec2 m = mix(min(lat_lo * lat_lo, lat_hi * lat_hi), vec2(0.0),
                     lessThanEqual(lat_lo * lat_hi, vec2(0.0)));
        float denom2 = m.x + m.y + z_max * z_max;
        if (!(denom2 > 0.0)) return 1.0;  // the box touches the origin
        return min(1.0, z_max / sqrt(denom2));
    }
    vec2 m = max(lat_lo * lat_lo, lat_hi * lat_hi);
    float denom2 = m.x + m.y + z_max * z_max;
    return max(-1.0, z_max / sqrt(denom2));
}

// lightcuts/compact_node.h's octahedral unit vector (2 x snorm16).
vec3 decode_octahedral(uint bits) {
    vec2 e = unpackSnorm2x16(bits);
    vec3 v = vec3(e, 1.0 - abs(e.x) - abs(e.y));
    if (v.z < 0.0) {
        vec2 sign_not_zero = mix(vec2(1.0), vec2(-1.0), lessThan(e, vec2(0.0)));
        v.xy = (1.0 - abs(e.yx)) * sign_not_zero;
    }
    return normalize(v);
}

// True when no spot of the cluster can reach x: each spot emits within pi/2 of
// its direction, every direction lies within beta of the cone axis, so a point
// seen from the box at more than pi/2 + beta from the axis is dark.
bool spot_cluster_excluded(GpuTreeNode node, vec3 x) {
    if (!(node.cone_cos >= -1.0 && node.cone_cos <= 1.0)) return false;
    float limit = 0.5 * kPi + acos(node.cone_cos);
    if (limit >= kPi) return false;
    vec3 axis = decode_octahedral(node.cone_axis);
    float cos_bound = max_cos_to_box(axis, x - node.bbox_max, x - node.bbox_min);
    return acos(clamp(cos_bound, -1.0, 1.0)) > limit + 1e-6;
}

// Upper bound of G (cosine with the normal included, visibility 1) over every
// light of a tree node (the node and its representative `rep`, loaded once by
// the caller) at point x with normal n.
float geometric_bound_of(GpuTreeNode node, GpuLight rep, vec3 x, vec3 n) {
    uint type = node.flags >> kNodeTypeShift;
    if (kDirectionalLights && type == kLightDirectional) {
        // The box holds the directions d_i; light arrives along -d_i.
        return max(0.0, max_cos_to_box(n, -node.bbox_max, -node.bbox_min));
    }
    // Every light's sphere of influence lies inside the node's radius around
    // the representative; a leaf uses its own range; unbounded stays unbounded.
    bool leaf = node.first_child == kEndOfWalk;
    float radius = leaf ? (rep.range > 0.0 ? rep.range : -1.0) : node.radius;
    if (rep.range <= 0.0) radius = -1.0;
    if (radius >= 0.0 && length(x - rep.position) >= radius) return 0.0;
    vec3 closest = clamp(x, node.bbox_min, node.bbox_max);
    float dmin2 = dot(x - closest, x - closest);
    float window = radius >= 0.0 ? range_window(sqrt(dmin2), radius) : 1.0;
    if (!(window > 0.0)) return 0.0;
    float cos_bound = max_cos_to_box(n, node.bbox_min - x, node.bbox_max - x);
    if (!(cos_bound > 0.0)) return 0.0;
    if (kSpotLights && type == kLightSpot && spot_cluster_excluded(node, x)) return 0.0;
    return cos_bound * window * inverse_square(dmin2);
}

// Upper bound of f_r at p over every light of a node whose representative has
// type `type`: the diffuse term plus the lobe at the largest cosine between the
// mirror direction and a direction into the node's box (cpu_evaluator's
// material_bound).
vec3 material_bound_of(uint type, GpuTreeNode node, SurfacePoint p) {
    vec3 f = p.albedo * (1.0 / kPi);
    if (!has_lobe(p)) return f;
    bool directional = kDirectionalLights && type == kLightDirectional;
    float c = directional ? max_cos_to_box(p.mirror, -node.bbox_max, -node.bbox_min)
                          : max_cos_to_box(p.mirror, node.bbox_min - p.position, node.bbox_max - p.position);
    return f + p.specular * glossy_lobe(c, p.exponent);
}

// Upper bound of f_r x G (visibility 1) per unit intensity over a node's lights.
vec3 response_bound_of(GpuTreeNode node, GpuLight rep, SurfacePoint p) {
    float g = geometric_bound_of(node, rep, p.position, p.normal);
    if (!(g > 0.0)) return vec3(0.0);
    return material_bound_of(node.flags >> kNodeTypeShift, node, p) * g;
}

#endif

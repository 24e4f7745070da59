// Upper bounds on what a light-tree cluster can contribute at a point, for
// the bound criterion (paper Sec. 4.1), written once: the shaders include it
// as GLSL (float), cpu_evaluator.cpp as C++ (double) in lc::shading. Each side
// fills a ClusterShape from its own node layout in one accessor.
#ifndef LC_DEVICE_CLUSTER_BOUNDS_GLSL_H
#define LC_DEVICE_CLUSTER_BOUNDS_GLSL_H

#include "lightcuts/device/material.glsl.h"
#include "lightcuts/device/shading.glsl.h"

#ifdef __cplusplus
namespace lc::shading {
using namespace lc::device;
#endif

// Relative slack on a bound, for the rounding of its own arithmetic. Below
// float's resolution, so a float bound is left as computed.
LC_CONST real kBoundSlack = 1e-9;
#ifdef __cplusplus
inline constexpr real kAngleSlack = 1e-9;  // radians, for a double acos
#else
const float kAngleSlack = 1e-6;  // radians, for a float acos
#endif

// What the bounds need to know about a tree node.
struct ClusterShape {
    bool directional;  // the representative's type, which every light shares
    bool spot;
    bool oriented;     // cosine emitters: the cone holds their normals
    bool leaf;
    real3 bbox_min;    // the lights' positions (directions when directional)
    real3 bbox_max;
    real3 position;    // the representative's
    real range;        // the representative's; <= 0: unbounded
    real radius;       // every light's sphere of influence lies within it around position
    real3 cone_axis;   // the spots' directions (oriented: normals) lie within the cone (axis, cone_cos)
    real cone_cos;     // -1: every direction
};

// Squares over the interval [lo, hi]: the smallest (0 when it holds 0) and the largest.
LC_INLINE real min_square_over(real lo, real hi) {
    return (lo <= 0.0 && hi >= 0.0) ? 0.0 : min(lo * lo, hi * hi);
}
LC_INLINE real max_square_over(real lo, real hi) { return max(lo * lo, hi * hi); }

// Upper bound of cos(angle(axis, v)) over every vector v in the box [lo, hi]
// (paper Eq. 4): rotate the box into a frame whose z is `axis`, take the
// rotated box's bounding box (centre rotated, half extents through |R|: the
// eight rotated corners' box, at a third of the work), then bound v_z / |v|
// using the largest v_z and the smallest (or largest) v_x^2 + v_y^2.
LC_INLINE real max_cos_to_box(real3 axis, real3 lo, real3 hi) {
    // Orthonormal frame (t, s, axis); Duff et al.'s branchless construction.
    real sign_z = copysign_one(axis.z);
    real a = -1.0 / (sign_z + axis.z);
    real b = axis.x * axis.y * a;
    real3 t = real3(1.0 + sign_z * axis.x * axis.x * a, sign_z * b, -sign_z * axis.x);
    real3 s = real3(b, sign_z + axis.y * axis.y * a, -axis.y);

    real3 center = 0.5 * (lo + hi);
    real3 half_extent = 0.5 * (hi - lo);
    real3 local = real3(dot(center, t), dot(center, s), dot(center, axis));
    real3 reach = real3(dot(half_extent, abs(t)), dot(half_extent, abs(s)),
                        dot(half_extent, abs(axis)));
    // Rounding must not shrink the box: widen it by a few ulps of the largest
    // terms the dot products summed (a grazing corner cancels them).
    real3 magnitude = real3(dot(abs(center), abs(t)), dot(abs(center), abs(s)),
                            dot(abs(center), abs(axis)));
    reach += (magnitude + reach) * kFewUlps;
    real3 llo = local - reach;
    real3 lhi = local + reach;
    real z_max = lhi.z;
    if (z_max >= 0.0) {
        real denom2 = min_square_over(llo.x, lhi.x) + min_square_over(llo.y, lhi.y) + z_max * z_max;
        if (!(denom2 > 0.0)) return 1.0;  // the box touches the origin
        return min(1.0, z_max / sqrt(denom2));
    }
    real denom2 = max_square_over(llo.x, lhi.x) + max_square_over(llo.y, lhi.y) + z_max * z_max;
    return max(-1.0, z_max / sqrt(denom2));
}

// True when no spot of the cluster can light x: every spot emits only within
// pi/2 of its own direction (outer <= pi/2), and every direction lies within
// beta of the cone axis, so an x seen from the box at more than pi/2 + beta
// from the axis is dark. Per-light outer angles are not stored on the node,
// so pi/2 is the only safe one.
LC_INLINE bool spot_cluster_excluded(LC_IN(ClusterShape) c, real3 x) {
    if (!(c.cone_cos >= -1.0 && c.cone_cos <= 1.0)) return false;
    real axis_len = length(c.cone_axis);
    if (!(axis_len > 0.0)) return false;
    real limit = kPi / 2.0 + acos(c.cone_cos);
    if (limit >= kPi) return false;
    // Vectors from the lights to x: x - y for y in the box.
    real cos_bound = max_cos_to_box(c.cone_axis / axis_len, x - c.bbox_max, x - c.bbox_min);
    return acos(clamp(cos_bound, -1.0, 1.0)) > limit + kAngleSlack;
}

// Upper bound of the emitter cosine (shading.glsl.h's emitter_cosine) over
// every oriented light of the cluster at x (paper Sec. 4.1): the directions
// from the lights to x lie in x - box, at least theta from the cone axis, and
// every normal within beta of it, so each angle to a normal is at least
// theta - beta: the bound is 1 when theta <= beta, else cos(theta - beta),
// expanded into products (no acos: float and double agree closely), 0 past
// pi/2.
LC_INLINE real oriented_emitter_bound(LC_IN(ClusterShape) c, real3 x) {
    if (!(c.cone_cos >= -1.0 && c.cone_cos <= 1.0)) return 1.0;
    real axis_len = length(c.cone_axis);
    if (!(axis_len > 0.0)) return 1.0;
    real cos_theta =
        clamp(max_cos_to_box(c.cone_axis / axis_len, x - c.bbox_max, x - c.bbox_min), -1.0, 1.0);
    if (cos_theta >= c.cone_cos) return 1.0;
    real sin_theta = sqrt(max(1.0 - cos_theta * cos_theta, 0.0));
    real sin_beta = sqrt(max(1.0 - c.cone_cos * c.cone_cos, 0.0));
    real bound = cos_theta * c.cone_cos + sin_theta * sin_beta;
    // theta - beta is in (0, pi], where the cosine falls: negative past pi/2
    // (the slack keeps a grazing angle's rounding from zeroing it).
    if (!(bound > -kAngleSlack)) return 0.0;
    return clamp(bound * (1.0 + kFewUlps) + kAngleSlack, 0.0, 1.0);
}

// Upper bound of G (shading.glsl.h, cosine with the normal included,
// visibility 1) over every light of the cluster at x with unit normal n.
LC_INLINE real cluster_geometric_bound(LC_IN(ClusterShape) c, real3 x, real3 n) {
    // The box holds the directions d_i; the light arrives along -d_i.
    if (c.directional) return max(0.0, max_cos_to_box(n, -c.bbox_max, -c.bbox_min));
    // A leaf uses its own range; an unbounded representative makes the node unbounded.
    real radius = c.leaf ? (c.range > 0.0 ? c.range : -1.0) : c.radius;
    if (c.range <= 0.0) radius = -1.0;
    if (radius >= 0.0 && length(x - c.position) >= radius) return 0.0;
    real3 closest = clamp(x, c.bbox_min, c.bbox_max);
    real dmin2 = dot(x - closest, x - closest);
    real window = radius >= 0.0 ? range_window(sqrt(dmin2), radius) : 1.0;
    if (!(window > 0.0)) return 0.0;
    real cos_bound = max_cos_to_box(n, c.bbox_min - x, c.bbox_max - x);
    if (!(cos_bound > 0.0)) return 0.0;
    if (c.spot && spot_cluster_excluded(c, x)) return 0.0;
    if (c.oriented) cos_bound *= oriented_emitter_bound(c, x);
    return cos_bound * window * inverse_square(dmin2);
}

// Upper bound, per channel, of f_r (material.glsl.h) at x over every light of
// the cluster: the diffuse term plus the lobe at the largest cosine between
// the mirror direction and a direction towards the box.
LC_INLINE real3 material_bound(LC_IN(ClusterShape) c, real3 albedo, real3 specular, real exponent,
                               real3 mirror, real3 x) {
    if (!has_lobe(specular, exponent)) return diffuse_brdf(albedo);
    real cos_max = c.directional ? max_cos_to_box(mirror, -c.bbox_max, -c.bbox_min)
                                 : max_cos_to_box(mirror, c.bbox_min - x, c.bbox_max - x);
    // The lobe's own rounding (pow of a number near 1) gets the same slack as G.
    return diffuse_brdf(albedo) + specular * (glossy_lobe(cos_max, exponent) * (1.0 + kBoundSlack));
}

// Upper bound, per channel, of f_r x G (visibility 1) per unit intensity over
// every light of the cluster, at x with unit normal n.
LC_INLINE real3 response_bound(LC_IN(ClusterShape) c, real3 albedo, real3 specular, real exponent,
                               real3 mirror, real3 x, real3 n) {
    real g = cluster_geometric_bound(c, x, n) * (1.0 + kBoundSlack);
    if (!(g > 0.0)) return real3(0.0);
    return material_bound(c, albedo, specular, exponent, mirror, x) * g;
}

#ifdef __cplusplus
}  // namespace lc::shading
#endif

#endif

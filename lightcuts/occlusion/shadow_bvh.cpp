// The occluder BVH: binned SAH built top-down, large ranges' two sides in
// parallel and small ones from an explicit work list, emitted in pre-order
// with escapes, then collapsed 4-wide for the any-hit walk.
#include "lightcuts/occlusion/shadow_bvh.h"

#include <glm/geometric.hpp>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "lightcuts/occlusion/wide_bvh.h"

namespace lc {
namespace {

// Binned SAH: this many bins per axis, on all three axes of the centroid bounds.
constexpr uint32_t kSahBins = 16;
// Past a depth every split is an object median. SAH alone may peel a few
// triangles off per level (a geometric chain does), so the depth could grow
// like the count; the medians bound it by that depth + log2(count). The first
// depth whose wide walk fits kBvhStackSize is kept: with medians alone a wide
// level spans two binary ones, and 2^29 triangles need 43 entries at most.
constexpr std::array<uint32_t, 4> kMaxSahDepths{48, 24, 12, 0};
// Ranges at least this large build their two sides as parallel tasks; smaller
// ones build serially (the same nodes either way).
constexpr uint32_t kParallelGrain = 4096;
// A leaf's word keeps kBvhLeafCountBits for the count, the rest for the first index.
constexpr size_t kMaxTriangles = (size_t{1} << (32 - kBvhLeafCountBits)) - 1;

// Each slab distance (b - o) * (1 / d) carries up to three roundings; widening
// the exit by 2 * gamma(3) keeps every box the exact ray touches (pbrt-v3, 3.9.2).
constexpr double kUnitRoundoff = std::numeric_limits<double>::epsilon() * 0.5;
constexpr double kGamma3 = 3.0 * kUnitRoundoff / (1.0 - 3.0 * kUnitRoundoff);
constexpr double kSlabExitScale = 1.0 + 2.0 * kGamma3;

constexpr float kFloatInf = std::numeric_limits<float>::infinity();

// Float boxes throughout the build: triangle vertices are floats, so the unions
// are exact and the node boxes need no rounding of their own.
struct FloatBox {
    glm::vec3 lo{kFloatInf};
    glm::vec3 hi{-kFloatInf};

    void grow(const glm::vec3& p_lo, const glm::vec3& p_hi) {
        lo = glm::min(lo, p_lo);
        hi = glm::max(hi, p_hi);
    }
    void grow(const FloatBox& other) { grow(other.lo, other.hi); }

    // Half the surface area, in double: float extents near FLT_MAX would overflow.
    double half_area() const {
        const glm::dvec3 e = glm::dvec3(hi) - glm::dvec3(lo);
        return e.x * e.y + e.y * e.z + e.z * e.x;
    }
};

// What the build moves around: the records themselves are partitioned (not an
// index array), so every pass reads memory in order.
struct BuildTriangle {
    glm::vec3 lo;
    glm::vec3 hi;
    glm::vec3 centroid;  // of the bounds; only steers the splits
    uint32_t index;      // into the kept triangles: the deterministic tie-break
};

struct BuildTask {
    uint32_t begin;
    uint32_t end;
    uint32_t depth;
};

bool is_finite(const glm::vec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

bool is_finite(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

// Zero area as the double test sees it: the edges' cross product vanishes (no
// overflow: float differences squared stay far below the double range).
bool has_zero_area(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::dvec3 n = glm::cross(glm::dvec3(b) - glm::dvec3(a), glm::dvec3(c) - glm::dvec3(a));
    return n.x == 0.0 && n.y == 0.0 && n.z == 0.0;
}

// The centroid bin of c on one axis; clamps the top edge and any rounding.
uint32_t bin_of(float c, double c_min, double bins_per_unit) {
    const double x = (static_cast<double>(c) - c_min) * bins_per_unit;
    if (!(x > 0.0)) return 0;
    if (x >= static_cast<double>(kSahBins - 1)) return kSahBins - 1;
    return static_cast<uint32_t>(x);
}

// Splits [begin, end) after the plane of least SAH cost over the 16 bins of each
// axis whose centroids spread; returns the first index of the right side, or
// nothing when every centroid coincides. The first of equal costs wins (x, y,
// z; low planes first), so the choice is deterministic.
std::optional<uint32_t> sah_split(std::vector<BuildTriangle>& tris, uint32_t begin, uint32_t end,
                                  const FloatBox& centroid_bounds) {
    struct Bin {
        FloatBox box;
        uint32_t count = 0;
    };
    double best_cost = std::numeric_limits<double>::infinity();
    int best_axis = -1;
    uint32_t best_plane = 0;  // left side: bins 0..best_plane
    std::array<double, 3> bins_per_unit{};
    for (int axis = 0; axis < 3; ++axis) {
        const double extent =
            static_cast<double>(centroid_bounds.hi[axis]) - static_cast<double>(centroid_bounds.lo[axis]);
        if (!(extent > 0.0)) continue;
        bins_per_unit[axis] = kSahBins / extent;
        std::array<Bin, kSahBins> bins;
        for (uint32_t i = begin; i < end; ++i) {
            const BuildTriangle& t = tris[i];
            Bin& bin = bins[bin_of(t.centroid[axis], centroid_bounds.lo[axis], bins_per_unit[axis])];
            bin.box.grow(t.lo, t.hi);
            ++bin.count;
        }
        // Sweep from the right for the right sides' areas, then from the left.
        std::array<double, kSahBins> right_area{};
        std::array<uint32_t, kSahBins> right_count{};
        FloatBox right_box;
        uint32_t right_n = 0;
        for (uint32_t b = kSahBins - 1; b > 0; --b) {
            right_box.grow(bins[b].box);
            right_n += bins[b].count;
            right_area[b] = right_n > 0 ? right_box.half_area() : 0.0;
            right_count[b] = right_n;
        }
        FloatBox left_box;
        uint32_t left_n = 0;
        for (uint32_t plane = 0; plane + 1 < kSahBins; ++plane) {
            left_box.grow(bins[plane].box);
            left_n += bins[plane].count;
            const uint32_t right_of_plane = right_count[plane + 1];
            if (left_n == 0 || right_of_plane == 0) continue;
            const double cost = left_box.half_area() * left_n + right_area[plane + 1] * right_of_plane;
            if (cost < best_cost) {
                best_cost = cost;
                best_axis = axis;
                best_plane = plane;
            }
        }
    }
    if (best_axis < 0) return std::nullopt;

    // Partition in place by the same bin function, so the sides match the sweep.
    const double c_min = centroid_bounds.lo[best_axis];
    const double per_unit = bins_per_unit[best_axis];
    auto goes_left = [&](const BuildTriangle& t) {
        return bin_of(t.centroid[best_axis], c_min, per_unit) <= best_plane;
    };
    uint32_t lo = begin;
    uint32_t hi = end;
    while (lo < hi) {
        if (goes_left(tris[lo])) {
            ++lo;
        } else {
            --hi;
            std::swap(tris[lo], tris[hi]);
        }
    }
    if (lo == begin || lo == end) return std::nullopt;  // cannot happen: both sides counted
    return lo;
}

// The object median on the centroids' longest axis, ordered by (centroid, index):
// a strict total order, so even identical triangles split evenly and the same
// way every time.
uint32_t median_split(std::vector<BuildTriangle>& tris, uint32_t begin, uint32_t end,
                      const FloatBox& centroid_bounds) {
    const glm::dvec3 extent = glm::dvec3(centroid_bounds.hi) - glm::dvec3(centroid_bounds.lo);
    int axis = 0;
    if (extent.y > extent[axis]) axis = 1;
    if (extent.z > extent[axis]) axis = 2;
    const uint32_t mid = begin + (end - begin) / 2;
    std::nth_element(tris.begin() + begin, tris.begin() + mid, tris.begin() + end,
                     [axis](const BuildTriangle& a, const BuildTriangle& b) {
                         if (a.centroid[axis] != b.centroid[axis]) return a.centroid[axis] < b.centroid[axis];
                         return a.index < b.index;
                     });
    return mid;
}

// One float ulp outward (never past the largest float): the box stays a
// conservative bound of the float triangles, with a margin for the shaders'
// float slab test.
void store_widened_bounds(const FloatBox& box, GpuBvhNode& node) {
    constexpr float kLowest = std::numeric_limits<float>::lowest();
    constexpr float kMax = std::numeric_limits<float>::max();
    for (int a = 0; a < 3; ++a) {
        node.bbox_min[a] = std::nextafter(box.lo[a], kLowest);
        node.bbox_max[a] = std::nextafter(box.hi[a], kMax);
    }
}

uint32_t saturate_u32(size_t n) {
    return static_cast<uint32_t>(std::min<size_t>(n, std::numeric_limits<uint32_t>::max()));
}

// Does origin + t * direction, 0 <= t <= t_max, touch the box [lo, hi]? A zero
// direction component is a containment test (its slab would give 0 * inf =
// NaN on a face); the comparisons are written so a NaN from an overflowing
// 1 / (denormal) leaves the interval unchanged, never a false miss.
bool segment_touches_box(const glm::dvec3& origin, const glm::dvec3& direction,
                         const glm::dvec3& inv_direction, double t_max, const glm::dvec3& lo,
                         const glm::dvec3& hi) {
    double t_enter = 0.0;
    double t_exit = t_max;
    for (int a = 0; a < 3; ++a) {
        if (direction[a] == 0.0) {
            if (origin[a] < lo[a] || origin[a] > hi[a]) return false;
            continue;
        }
        double t_near = (lo[a] - origin[a]) * inv_direction[a];
        double t_far = (hi[a] - origin[a]) * inv_direction[a];
        if (inv_direction[a] < 0.0) std::swap(t_near, t_far);
        if (t_near > t_enter) t_enter = t_near;
        if (t_far < t_exit) t_exit = t_far;
    }
    return t_enter <= t_exit * kSlabExitScale;
}

// A wide node's slot box, in double (exact: the floats convert exactly).
void slot_box(const GpuWideBvhNode& node, int slot, glm::dvec3& lo, glm::dvec3& hi) {
    lo = glm::dvec3(node.lo_x[slot], node.lo_y[slot], node.lo_z[slot]);
    hi = glm::dvec3(node.hi_x[slot], node.hi_y[slot], node.hi_z[slot]);
}

// Moller-Trumbore, both faces: a hit strictly inside (0, t_max). The barycentric
// tests are negated so a NaN (a near-parallel ray whose 1 / det overflows) misses.
// u and w: the hit's barycentric weights of v[1] and v[2].
bool segment_hits_triangle(const glm::dvec3& origin, const glm::dvec3& direction, double t_max,
                           const glm::dvec3* v, double& u, double& w) {
    const glm::dvec3 edge1 = v[1] - v[0];
    const glm::dvec3 edge2 = v[2] - v[0];
    const glm::dvec3 p = glm::cross(direction, edge2);
    const double det = glm::dot(edge1, p);
    if (det == 0.0) return false;  // the ray is parallel to (or in) the triangle's plane
    const double inv_det = 1.0 / det;
    const glm::dvec3 s = origin - v[0];
    u = glm::dot(s, p) * inv_det;
    if (!(u >= 0.0 && u <= 1.0)) return false;
    const glm::dvec3 q = glm::cross(s, edge1);
    w = glm::dot(direction, q) * inv_det;
    if (!(w >= 0.0 && u + w <= 1.0)) return false;
    const double t = glm::dot(edge2, q) * inv_det;
    return t > 0.0 && t < t_max;
}

}  // namespace

ShadowBvh ShadowBvh::build(const Scene& scene) {
    std::vector<glm::vec3> casting;
    OccluderMasks masks;
    const std::vector<int32_t> mesh_mask = mesh_alpha_masks(scene, masks.masks);
    size_t skipped_degenerate = 0;
    size_t skipped_non_casting = 0;
    for (size_t m = 0; m < scene.meshes.size(); ++m) {
        const Mesh& mesh = scene.meshes[m];
        const size_t full_triples = mesh.indices.size() / 3;
        // A trailing partial triple is no triangle: count it as a degenerate one.
        if (mesh.indices.size() % 3 != 0) ++skipped_degenerate;
        const int32_t mask = mesh_mask[m];
        if (!casts_shadows(scene, mesh) || (mask >= 0 && mask_cuts_everything(masks.masks[size_t(mask)]))) {
            skipped_non_casting += full_triples;
            continue;
        }
        for (size_t t = 0; t < full_triples; ++t) {
            const uint32_t* idx = &mesh.indices[3 * t];
            const size_t n = mesh.positions.size();
            if (idx[0] >= n || idx[1] >= n || idx[2] >= n) {
                ++skipped_degenerate;
                continue;
            }
            add_occluder_mask(masks, casting.size() / 3, mesh, idx, mask);
            casting.push_back(mesh.positions[idx[0]]);
            casting.push_back(mesh.positions[idx[1]]);
            casting.push_back(mesh.positions[idx[2]]);
        }
    }
    ShadowBvh bvh = build(std::span<const glm::vec3>(casting), masks);
    bvh.stats_.skipped_degenerate = saturate_u32(bvh.stats_.skipped_degenerate + skipped_degenerate);
    bvh.stats_.skipped_non_casting = saturate_u32(skipped_non_casting);
    return bvh;
}

ShadowBvh ShadowBvh::build(std::span<const glm::vec3> triangle_vertices) {
    return build(triangle_vertices, OccluderMasks{});
}

namespace {

// A range's subtree in pre-order, and its depth below the range's own node.
struct Subtree {
    std::vector<GpuBvhNode> nodes;
    uint32_t depth = 0;
};

// The node of a range: its widened bounds, a leaf when small enough. Splits
// the range (reordering its triangles) otherwise and returns where.
std::optional<uint32_t> make_node(std::vector<BuildTriangle>& tris, const BuildTask& task,
                                  uint32_t max_sah_depth, GpuBvhNode& node) {
    FloatBox bounds;
    FloatBox centroid_bounds;
    for (uint32_t i = task.begin; i < task.end; ++i) {
        bounds.grow(tris[i].lo, tris[i].hi);
        centroid_bounds.grow(tris[i].centroid, tris[i].centroid);
    }
    store_widened_bounds(bounds, node);
    const uint32_t n = task.end - task.begin;
    if (n <= kBvhMaxLeafSize) {
        node.triangles = (task.begin << kBvhLeafCountBits) | n;
        return std::nullopt;
    }
    node.triangles = 0;  // inner: first child next
    std::optional<uint32_t> mid;
    if (task.depth < max_sah_depth) mid = sah_split(tris, task.begin, task.end, centroid_bounds);
    if (!mid) mid = median_split(tris, task.begin, task.end, centroid_bounds);
    return mid;
}

// Serially, with an explicit LIFO of ranges: the left range is popped (and so
// emitted) right after its parent, and all of its subtree before the right
// range: the nodes come out in pre-order.
void build_serial(std::vector<BuildTriangle>& tris, const BuildTask& root, uint32_t max_sah_depth,
                  Subtree& out) {
    std::vector<BuildTask> work{root};
    while (!work.empty()) {
        const BuildTask task = work.back();
        work.pop_back();
        out.depth = std::max(out.depth, task.depth - root.depth);
        GpuBvhNode node;
        const std::optional<uint32_t> mid = make_node(tris, task, max_sah_depth, node);
        out.nodes.push_back(node);
        if (!mid) continue;
        work.push_back({*mid, task.end, task.depth + 1});
        work.push_back({task.begin, *mid, task.depth + 1});
    }
}

// A large range splits, then its sides build as two tasks on disjoint
// triangles and are joined in order: the nodes do not depend on the threads.
Subtree build_subtree(std::vector<BuildTriangle>& tris, const BuildTask& task, uint32_t max_sah_depth) {
    Subtree out;
    if (task.end - task.begin < kParallelGrain) {
        build_serial(tris, task, max_sah_depth, out);
        return out;
    }
    GpuBvhNode node;
    const std::optional<uint32_t> mid = make_node(tris, task, max_sah_depth, node);
    out.nodes.push_back(node);
    if (!mid) return out;
    Subtree left;
    Subtree right;
    tbb::parallel_invoke(
        [&] { left = build_subtree(tris, {task.begin, *mid, task.depth + 1}, max_sah_depth); },
        [&] { right = build_subtree(tris, {*mid, task.end, task.depth + 1}, max_sah_depth); });
    out.nodes.reserve(1 + left.nodes.size() + right.nodes.size());
    out.nodes.insert(out.nodes.end(), left.nodes.begin(), left.nodes.end());
    out.nodes.insert(out.nodes.end(), right.nodes.begin(), right.nodes.end());
    out.depth = 1 + std::max(left.depth, right.depth);
    return out;
}

// Escapes from subtree sizes, children after parents: size(i) = 1 for a leaf,
// else 1 + size(left) + size(right) with left = i + 1, right = i + 1 + size(left).
void link_escapes(std::vector<GpuBvhNode>& nodes) {
    const size_t node_count = nodes.size();
    std::vector<uint32_t> subtree_size(node_count, 1);
    for (size_t i = node_count; i-- > 0;) {
        if (nodes[i].triangles != 0) continue;
        const size_t left = i + 1;
        const size_t right = left + subtree_size[left];
        subtree_size[i] = 1 + subtree_size[left] + subtree_size[right];
    }
    for (size_t i = 0; i < node_count; ++i) {
        const size_t escape = i + subtree_size[i];
        nodes[i].escape = escape == node_count ? kEndOfWalk : static_cast<int32_t>(escape);
    }
}

struct Layouts {
    std::vector<GpuBvhNode> binary;
    uint32_t binary_depth = 0;
    WideBvh wide;
    uint32_t max_sah_depth = 0;
};

// The binary and wide layouts, with the deepest SAH whose wide walk fits the
// shaders' stack (lightcuts/device/gpu_structs.h). Leaves `tris` in leaf order.
Layouts build_layouts(std::vector<BuildTriangle>& tris) {
    const std::vector<BuildTriangle> input = tris;
    for (uint32_t max_sah_depth : kMaxSahDepths) {
        tris = input;
        Subtree tree = build_subtree(tris, {0, uint32_t(tris.size()), 0}, max_sah_depth);
        link_escapes(tree.nodes);
        WideBvh wide = collapse_to_wide(tree.nodes);
        if (wide.stack_need > kBvhStackSize) continue;
        return {std::move(tree.nodes), tree.depth, std::move(wide), max_sah_depth};
    }
    // Unreachable below kMaxTriangles: medians alone need at most 43 entries.
    throw std::length_error("shadow BVH: even an object-median tree over " + std::to_string(tris.size()) +
                            " triangles needs more than " + std::to_string(kBvhStackSize) +
                            " stack entries to walk");
}

}  // namespace

ShadowBvh ShadowBvh::build(std::span<const glm::vec3> triangle_vertices, const OccluderMasks& masks) {
    ShadowBvh bvh;
    size_t skipped = triangle_vertices.size() % 3 != 0 ? 1 : 0;  // a trailing partial triangle

    // Keep the finite triangles of nonzero area.
    std::vector<BuildTriangle> tris;
    const size_t input_count = triangle_vertices.size() / 3;
    tris.reserve(std::min(input_count, kMaxTriangles));
    for (size_t t = 0; t < input_count; ++t) {
        const glm::vec3& a = triangle_vertices[3 * t];
        const glm::vec3& b = triangle_vertices[3 * t + 1];
        const glm::vec3& c = triangle_vertices[3 * t + 2];
        if (!is_finite(a) || !is_finite(b) || !is_finite(c) || has_zero_area(a, b, c)) {
            ++skipped;
            continue;
        }
        // 2^29 - 1 triangles is the most a leaf word can address; a scene past it
        // (over 19 GB of float vertices) keeps the first ones and counts the rest here.
        if (tris.size() == kMaxTriangles) {
            ++skipped;
            continue;
        }
        BuildTriangle bt;
        bt.lo = glm::min(a, glm::min(b, c));
        bt.hi = glm::max(a, glm::max(b, c));
        bt.centroid = 0.5f * bt.lo + 0.5f * bt.hi;  // halves first: lo + hi may overflow
        bt.index = static_cast<uint32_t>(t);
        tris.push_back(bt);
    }
    bvh.stats_.skipped_degenerate = saturate_u32(skipped);
    bvh.stats_.triangles = static_cast<uint32_t>(tris.size());
    if (tris.empty()) return bvh;

    const uint32_t count = static_cast<uint32_t>(tris.size());
    Layouts layouts = build_layouts(tris);
    bvh.nodes_ = std::move(layouts.binary);
    bvh.wide_nodes_ = std::move(layouts.wide.nodes);
    bvh.stats_.depth = layouts.binary_depth;
    bvh.stats_.wide_nodes = static_cast<uint32_t>(bvh.wide_nodes_.size());
    bvh.stats_.wide_leaves = layouts.wide.leaves;
    bvh.stats_.wide_depth = layouts.wide.depth;
    bvh.stats_.stack_need = layouts.wide.stack_need;
    bvh.stats_.max_sah_depth = layouts.max_sah_depth;
    const size_t node_count = bvh.nodes_.size();

    // The triangles in leaf order: floats (vertex and edges) for the shaders,
    // the exact vertices in double for the CPU test.
    bvh.triangles_.resize(count);
    bvh.vertices_.resize(3 * static_cast<size_t>(count));
    for (uint32_t i = 0; i < count; ++i) {
        const size_t source = 3 * static_cast<size_t>(tris[i].index);
        const glm::dvec3 v0(triangle_vertices[source]);
        const glm::dvec3 v1(triangle_vertices[source + 1]);
        const glm::dvec3 v2(triangle_vertices[source + 2]);
        bvh.vertices_[3 * size_t{i}] = v0;
        bvh.vertices_[3 * size_t{i} + 1] = v1;
        bvh.vertices_[3 * size_t{i} + 2] = v2;
        GpuShadowTriangle& g = bvh.triangles_[i];
        g.v0 = glm::vec3(v0);
        g.edge1 = glm::vec3(v1 - v0);
        g.edge2 = glm::vec3(v2 - v0);
    }
    bvh.stats_.nodes = static_cast<uint32_t>(node_count);
    bvh.sources_.resize(count);
    for (uint32_t i = 0; i < count; ++i) bvh.sources_[i] = tris[i].index;
    if (masks.any()) bvh.attach_masks(masks, bvh.sources_);
    return bvh;
}

// The masked triangles in leaf order, their masks and the masks' texels
// packed sixteen to a GpuMaskTexels. A triangle the list does not cover, or
// with a mask index out of range, stays opaque.
void ShadowBvh::attach_masks(const OccluderMasks& masks, std::span<const uint32_t> source_of_leaf) {
    masks_ = masks.masks;
    size_t texel_count = 0;
    for (const AlphaMask& mask : masks_) {
        GpuAlphaMask g;
        g.texel_offset = static_cast<uint32_t>(texel_count);
        g.width = static_cast<uint32_t>(mask.width);
        g.height = static_cast<uint32_t>(mask.height);
        g.keep_threshold = mask.keep_threshold;
        gpu_masks_.push_back(g);
        texel_count += mask.alpha.size();
    }
    gpu_texels_.assign((texel_count + 15) / 16, GpuMaskTexels{});
    size_t at = 0;
    for (const AlphaMask& mask : masks_) {
        for (uint8_t a : mask.alpha) {
            gpu_texels_[at / 16].words[int((at / 4) % 4)] |= uint32_t(a) << (8 * (at % 4));
            ++at;
        }
    }
    for (size_t i = 0; i < source_of_leaf.size(); ++i) {
        const size_t source = source_of_leaf[i];
        if (source >= masks.triangle_mask.size() || 3 * source + 2 >= masks.triangle_uvs.size()) continue;
        const int32_t mask = masks.triangle_mask[source];
        if (mask < 0 || size_t(mask) >= masks_.size()) continue;
        GpuMaskedTriangle g;
        g.uv0 = masks.triangle_uvs[3 * source];
        g.uv1 = masks.triangle_uvs[3 * source + 1];
        g.uv2 = masks.triangle_uvs[3 * source + 2];
        g.mask = static_cast<uint32_t>(mask);
        triangles_[i].masked = static_cast<uint32_t>(gpu_masked_.size()) + 1;
        gpu_masked_.push_back(g);
    }
    stats_.masked = static_cast<uint32_t>(gpu_masked_.size());
}

// Does the leaf-order triangle block a ray at barycentrics (u, w)? The
// texture coordinate is interpolated in float, as the shaders do.
bool ShadowBvh::blocks(size_t leaf_triangle, double u, double w) const {
    const uint32_t masked = triangles_[leaf_triangle].masked;
    if (masked == 0) return true;
    const GpuMaskedTriangle& m = gpu_masked_[masked - 1];
    const float fu = static_cast<float>(u);
    const float fw = static_cast<float>(w);
    const glm::vec2 uv = m.uv0 * (1.0f - fu - fw) + m.uv1 * fu + m.uv2 * fw;
    return mask_keeps(masks_[m.mask], uv);
}

bool ShadowBvh::occluded(const glm::dvec3& origin, const glm::dvec3& direction, double t_max) const {
    if (wide_nodes_.empty() || !(t_max > 0.0)) return false;
    if (!is_finite(origin) || !is_finite(direction)) return false;
    const glm::dvec3 inv_direction = 1.0 / direction;  // +-inf on zero components
    const uint32_t octant = direction_octant(direction.x < 0.0, direction.y < 0.0, direction.z < 0.0);
    // The build keeps stack_need <= kBvhStackSize, so the pushes never overflow.
    std::array<uint32_t, kBvhStackSize> stack;
    size_t size = 0;
    uint32_t entry = 0;  // the root, an inner entry (count 0)
    for (;;) {
        const uint32_t count = entry & kBvhLeafCountMask;
        const uint32_t index = entry >> kBvhLeafCountBits;
        if (count != 0) {
            for (uint32_t k = 0; k < count; ++k) {
                const glm::dvec3* v = &vertices_[3 * (static_cast<size_t>(index) + k)];
                double u = 0.0, w = 0.0;
                if (segment_hits_triangle(origin, direction, t_max, v, u, w) &&
                    blocks(static_cast<size_t>(index) + k, u, w))
                    return true;
            }
        } else {
            // The hit slots, farthest pushed first so the nearest pops next.
            const GpuWideBvhNode& node = wide_nodes_[index];
            const uint32_t order = slot_order(node, octant);
            for (uint32_t k = kBvhWidth; k-- > 0;) {
                const int slot = int((order >> (2 * k)) & 3u);
                const uint32_t child = node.children[slot];
                if (child == kBvhEmptyChild) continue;
                glm::dvec3 lo, hi;
                slot_box(node, slot, lo, hi);
                if (segment_touches_box(origin, direction, inv_direction, t_max, lo, hi)) stack[size++] = child;
            }
        }
        if (size == 0) return false;
        entry = stack[--size];
    }
}

}  // namespace lc

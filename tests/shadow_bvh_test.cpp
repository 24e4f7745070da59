// The shadow-ray BVH (lightcuts/occlusion/shadow_bvh.h): any-hit answers equal
// a brute-force loop over every triangle, the stackless layout is a valid
// pre-order tree with conservative float boxes, its 4-wide collapse holds
// the same leaves with nearest-first orders and a bounded stack, the build
// is the same at any thread count, and the hard cases (empty, identical,
// chained, far-away, axis-parallel, degenerate) stay correct.
#include "lightcuts/occlusion/shadow_bvh.h"

#include <gtest/gtest.h>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <tbb/task_arena.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <utility>
#include <vector>

#include "lightcuts/occlusion/wide_bvh.h"

namespace lc::client {
namespace {

using Triangles = std::vector<glm::vec3>;  // 3 vertices per triangle

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr float kFloatNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kFloatInf = std::numeric_limits<float>::infinity();

// Fixed-seed random numbers with our own conversion to [0, 1), so the streams
// do not depend on the standard library's distributions.
class Rng {
public:
    explicit Rng(uint64_t seed) : engine_(seed) {}
    double uniform() { return static_cast<double>(engine_() >> 11) * 0x1p-53; }
    double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
    glm::dvec3 point(const glm::dvec3& lo, const glm::dvec3& hi) {
        const double x = uniform(lo.x, hi.x);
        const double y = uniform(lo.y, hi.y);
        const double z = uniform(lo.z, hi.z);
        return {x, y, z};
    }
    size_t index(size_t n) { return static_cast<size_t>(uniform() * static_cast<double>(n)); }

private:
    std::mt19937_64 engine_;
};

struct Ray {
    glm::dvec3 origin;
    glm::dvec3 direction;
    double t_max;
};

// --- The reference: every triangle, Moller-Trumbore in double -----------------

enum class Reference { kMiss, kHit, kAmbiguous };

// The loop over every triangle, with each triangle's double vertex and edges
// computed once, exactly as ShadowBvh computes them from the float vertices.
class BruteForce {
public:
    explicit BruteForce(const Triangles& tris) {
        for (size_t i = 0; i + 2 < tris.size(); i += 3) {
            const glm::dvec3 v0(tris[i]);
            const glm::dvec3 v1(tris[i + 1]);
            const glm::dvec3 v2(tris[i + 2]);
            tris_.push_back({v0, v1 - v0, v2 - v0});
            boxes_.push_back({glm::min(v0, glm::min(v1, v2)), glm::max(v0, glm::max(v1, v2))});
        }
    }

    // Occluded by any triangle? Ambiguous when a crossing lies within 1e-9
    // (relative to t_max) of either end and no crossing lies clearly inside.
    Reference classify(const Ray& ray) const {
        const double margin = 1e-9 * ray.t_max;
        const Box reach = segment_reach(ray);
        bool ambiguous = false;
        for (size_t i = 0; i < tris_.size(); ++i) {
            if (!overlap(reach, boxes_[i])) continue;
            double t = 0.0;
            if (!line_crosses(ray, tris_[i], t)) continue;
            if (std::abs(t) <= margin || std::abs(t - ray.t_max) <= margin) {
                ambiguous = true;
                continue;
            }
            if (t > 0.0 && t < ray.t_max) return Reference::kHit;
        }
        return ambiguous ? Reference::kAmbiguous : Reference::kMiss;
    }

    // The same without the ambiguity (for exactly representable setups).
    bool occluded(const Ray& ray) const {
        const Box reach = segment_reach(ray);
        for (size_t i = 0; i < tris_.size(); ++i) {
            double t = 0.0;
            if (overlap(reach, boxes_[i]) && line_crosses(ray, tris_[i], t) && t > 0.0 && t < ray.t_max)
                return true;
        }
        return false;
    }

private:
    struct Triangle {
        glm::dvec3 v0;
        glm::dvec3 edge1;
        glm::dvec3 edge2;
    };
    struct Box {
        glm::dvec3 lo;
        glm::dvec3 hi;
    };

    // The segment's box, widened by 1e-7 of its size and position: a cheap,
    // per-triangle skip of triangles far from the segment, where the full
    // test (whose roundings are some 1e-16 of that) could not find a crossing
    // in t in [-1e-9, 1 + 1e-9] * t_max. It changes the speed, not the answer.
    static Box segment_reach(const Ray& ray) {
        if (!std::isfinite(ray.t_max)) return {glm::dvec3(-kInf), glm::dvec3(kInf)};
        const glm::dvec3 end = ray.origin + ray.direction * ray.t_max;
        const glm::dvec3 lo = glm::min(ray.origin, end);
        const glm::dvec3 hi = glm::max(ray.origin, end);
        const glm::dvec3 size = hi - lo;
        const double scale = std::max({size.x, size.y, size.z, std::abs(lo.x), std::abs(lo.y), std::abs(lo.z),
                                       std::abs(hi.x), std::abs(hi.y), std::abs(hi.z), 1e-300});
        const double margin = 1e-7 * scale;
        return {lo - margin, hi + margin};
    }

    static bool overlap(const Box& a, const Box& b) {
        return a.lo.x <= b.hi.x && b.lo.x <= a.hi.x && a.lo.y <= b.hi.y && b.lo.y <= a.hi.y &&
               a.lo.z <= b.hi.z && b.lo.z <= a.hi.z;
    }

    // Where the line origin + t * direction crosses the triangle, if it does:
    // Moller-Trumbore with the arithmetic of the definition (both faces, closed
    // edges, u and v as products with 1 / det).
    static bool line_crosses(const Ray& ray, const Triangle& tri, double& t) {
        const glm::dvec3 p = glm::cross(ray.direction, tri.edge2);
        const double det = glm::dot(tri.edge1, p);
        if (det == 0.0) return false;
        const glm::dvec3 s = ray.origin - tri.v0;
        const double u_det = glm::dot(s, p);
        // A quick reject for u clearly outside [0, 1] (a margin of 1e-6 dwarfs
        // the product's rounding), so that the division only runs near the
        // triangle; the answer is the same as without it.
        const double abs_det = std::abs(det);
        const double signed_u_det = det > 0.0 ? u_det : -u_det;
        if (signed_u_det < -1e-6 * abs_det || signed_u_det > (1.0 + 1e-6) * abs_det) return false;
        const double inv_det = 1.0 / det;
        const double u = u_det * inv_det;
        if (!(u >= 0.0 && u <= 1.0)) return false;
        const glm::dvec3 q = glm::cross(s, tri.edge1);
        const double v = glm::dot(ray.direction, q) * inv_det;
        if (!(v >= 0.0 && u + v <= 1.0)) return false;
        t = glm::dot(tri.edge2, q) * inv_det;
        return true;
    }

    std::vector<Triangle> tris_;
    std::vector<Box> boxes_;
};

// --- Scenes and rays ----------------------------------------------------------

// The triangles of `tris` whose area is not zero in double (the ones the
// build keeps), in order.
Triangles with_area(const Triangles& tris) {
    Triangles kept;
    for (size_t i = 0; i + 2 < tris.size(); i += 3) {
        const glm::dvec3 n = glm::cross(glm::dvec3(tris[i + 1]) - glm::dvec3(tris[i]),
                                        glm::dvec3(tris[i + 2]) - glm::dvec3(tris[i]));
        if (n != glm::dvec3(0.0)) kept.insert(kept.end(), {tris[i], tris[i + 1], tris[i + 2]});
    }
    return kept;
}

// `count` triangles with centres in center +- extent and vertices within
// +- size (0.2 .. 2 times) of their centre.
Triangles random_soup(size_t count, uint64_t seed, const glm::dvec3& center, double extent, double size) {
    Rng rng(seed);
    Triangles tris;
    tris.reserve(3 * count);
    for (size_t i = 0; i < count; ++i) {
        const glm::dvec3 c = rng.point(center - extent, center + extent);
        const double s = size * rng.uniform(0.2, 2.0);
        for (int k = 0; k < 3; ++k) tris.push_back(glm::vec3(c + rng.point(glm::dvec3(-s), glm::dvec3(s))));
    }
    return tris;
}

// A random segment or ray through the soup's region. Some directions have one
// or two zero components, with the origin on a vertex's coordinate or one
// float ulp off it (exactly on some boxes' faces, which sit one ulp outside).
Ray random_ray(Rng& rng, const Triangles& tris, const glm::dvec3& lo, const glm::dvec3& hi) {
    const glm::dvec3 a = rng.point(lo, hi);
    glm::dvec3 b = rng.point(lo, hi);
    if (rng.uniform() < 0.5) {
        // Aimed near a random triangle (inside it or just past an edge), ending
        // before or after it: many hits, misses and near-edge crossings.
        const size_t t = 3 * rng.index(tris.size() / 3);
        const double u = rng.uniform(-0.2, 1.0);
        const double v = rng.uniform(-0.2, 1.0 - std::max(u, 0.0));
        const glm::dvec3 v0(tris[t]);
        const glm::dvec3 target =
            v0 + u * (glm::dvec3(tris[t + 1]) - v0) + v * (glm::dvec3(tris[t + 2]) - v0);
        b = a + (target - a) * rng.uniform(0.6, 1.6);
    }
    Ray ray{a, b - a, 1.0};
    const size_t mode = rng.index(6);
    if (mode == 2) {
        const double length = glm::length(ray.direction);
        ray.direction /= length;
        ray.t_max = length;
    } else if (mode >= 3) {
        const int zeros = mode == 3 ? 1 : 2;
        const int first_axis = static_cast<int>(rng.index(3));
        for (int z = 0; z < zeros; ++z) {
            const int axis = (first_axis + z) % 3;
            ray.direction[axis] = 0.0;
            const float coordinate = tris[rng.index(tris.size())][axis];
            const size_t snap = rng.index(4);
            if (snap == 1) ray.origin[axis] = coordinate;
            if (snap == 2) ray.origin[axis] = std::nextafter(coordinate, -kFloatInf);
            if (snap == 3) ray.origin[axis] = std::nextafter(coordinate, kFloatInf);
        }
        if (ray.direction == glm::dvec3(0.0)) ray.direction[first_axis] = 1.0;
        ray.t_max = rng.uniform(0.0, 2.0) * glm::length(hi - lo);
    }
    return ray;
}

struct AgreementCounts {
    size_t hits = 0;
    size_t misses = 0;
    size_t ambiguous = 0;
    size_t disagreements = 0;
};

AgreementCounts compare_with_brute_force(const ShadowBvh& bvh, const Triangles& tris, size_t ray_count,
                                         uint64_t seed, const glm::dvec3& lo, const glm::dvec3& hi) {
    Rng rng(seed);
    const BruteForce reference(tris);
    AgreementCounts counts;
    for (size_t r = 0; r < ray_count; ++r) {
        const Ray ray = random_ray(rng, tris, lo, hi);
        const Reference expected = reference.classify(ray);
        if (expected == Reference::kAmbiguous) {
            ++counts.ambiguous;
            continue;
        }
        const bool want = expected == Reference::kHit;
        (want ? counts.hits : counts.misses) += 1;
        if (bvh.occluded(ray.origin, ray.direction, ray.t_max) != want) {
            if (++counts.disagreements <= 5)
                ADD_FAILURE() << "ray " << r << " origin (" << ray.origin.x << ", " << ray.origin.y << ", "
                              << ray.origin.z << ") direction (" << ray.direction.x << ", " << ray.direction.y
                              << ", " << ray.direction.z << ") t_max " << ray.t_max << ": brute force says "
                              << want;
        }
    }
    return counts;
}

// --- The layout -------------------------------------------------------------

// A triangle as the builder hands it to the shaders, as a sortable key.
using TriangleKey = std::array<float, 9>;

TriangleKey key_of(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const glm::vec3 e1(glm::dvec3(b) - glm::dvec3(a));
    const glm::vec3 e2(glm::dvec3(c) - glm::dvec3(a));
    return {a.x, a.y, a.z, e1.x, e1.y, e1.z, e2.x, e2.y, e2.z};
}

TriangleKey key_of(const GpuShadowTriangle& g) {
    return {g.v0.x, g.v0.y, g.v0.z, g.edge1.x, g.edge1.y, g.edge1.z, g.edge2.x, g.edge2.y, g.edge2.z};
}

bool inside(const glm::vec3& p, const glm::vec3& lo, const glm::vec3& hi) {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x <= hi.x && p.y <= hi.y && p.z <= hi.z;
}

bool slot_inside(const GpuWideBvhNode& inner, int t, const GpuWideBvhNode& outer, int s) {
    const glm::vec3 lo(inner.lo_x[t], inner.lo_y[t], inner.lo_z[t]);
    const glm::vec3 hi(inner.hi_x[t], inner.hi_y[t], inner.hi_z[t]);
    const glm::vec3 outer_lo(outer.lo_x[s], outer.lo_y[s], outer.lo_z[s]);
    const glm::vec3 outer_hi(outer.hi_x[s], outer.hi_y[s], outer.hi_z[s]);
    return inside(lo, outer_lo, outer_hi) && inside(hi, outer_lo, outer_hi);
}

// The stack a walk that hits every box needs, slots in their stored order:
// one order of the many the bound in the stats must cover.
uint32_t simulated_stack(const std::vector<GpuWideBvhNode>& wide) {
    std::vector<uint32_t> stack;
    size_t most = 0;
    uint32_t entry = 0;
    for (;;) {
        if ((entry & kBvhLeafCountMask) == 0) {
            const GpuWideBvhNode& node = wide[entry >> kBvhLeafCountBits];
            for (int s = int(kBvhWidth); s-- > 0;)
                if (node.children[s] != kBvhEmptyChild) stack.push_back(node.children[s]);
            most = std::max(most, stack.size());
        }
        if (stack.empty()) return static_cast<uint32_t>(most);
        entry = stack.back();
        stack.pop_back();
    }
}

// Checks the 4-wide layout against the binary one: each binary leaf is one
// wide leaf slot with the same word and box, inner slots name later nodes
// (each once) whose slots lie inside them, used slots come first, each
// octant's order is a permutation with the used slots first, and the stack
// bound and counts hold.
void expect_valid_wide_layout(const ShadowBvh& bvh) {
    const std::vector<GpuWideBvhNode>& wide = bvh.gpu_wide_nodes();
    const std::vector<GpuBvhNode>& binary = bvh.gpu_nodes();
    ASSERT_EQ(bvh.stats().wide_nodes, wide.size());
    if (binary.empty()) {
        EXPECT_TRUE(wide.empty());
        return;
    }
    ASSERT_FALSE(wide.empty());
    std::map<uint32_t, const GpuBvhNode*> binary_leaves;
    for (const GpuBvhNode& n : binary)
        if (n.triangles != 0) binary_leaves[n.triangles] = &n;
    std::vector<uint8_t> reached(wide.size(), 0);
    reached[0] = 1;
    size_t leaves = 0;
    for (size_t i = 0; i < wide.size(); ++i) {
        ASSERT_TRUE(reached[i]) << "wide node " << i << " is no one's child";
        const GpuWideBvhNode& node = wide[i];
        uint32_t used = 0;
        for (int s = 0; s < int(kBvhWidth); ++s) {
            const uint32_t child = node.children[s];
            if (child == kBvhEmptyChild) continue;
            ASSERT_EQ(uint32_t(s), used) << "node " << i << ": used slots come first";
            ++used;
            if ((child & kBvhLeafCountMask) != 0) {
                ++leaves;
                const auto found = binary_leaves.find(child);
                ASSERT_TRUE(found != binary_leaves.end()) << "node " << i << " slot " << s << ": no such leaf";
                const GpuBvhNode& leaf = *found->second;
                EXPECT_TRUE(node.lo_x[s] == leaf.bbox_min.x && node.lo_y[s] == leaf.bbox_min.y &&
                            node.lo_z[s] == leaf.bbox_min.z && node.hi_x[s] == leaf.bbox_max.x &&
                            node.hi_y[s] == leaf.bbox_max.y && node.hi_z[s] == leaf.bbox_max.z);
                binary_leaves.erase(found);
                continue;
            }
            const size_t c = child >> kBvhLeafCountBits;
            ASSERT_GT(c, i);
            ASSERT_LT(c, wide.size());
            ASSERT_FALSE(reached[c]) << "wide node " << c << " has two parents";
            reached[c] = 1;
            for (int t = 0; t < int(kBvhWidth); ++t) {
                if (wide[c].children[t] != kBvhEmptyChild) {
                    EXPECT_TRUE(slot_inside(wide[c], t, node, s)) << "node " << c << " sticks out of " << i;
                }
            }
        }
        ASSERT_GE(used, 1u);
        for (uint32_t octant = 0; octant < 8; ++octant) {
            const uint32_t order = slot_order(node, octant);
            uint32_t seen = 0;
            for (uint32_t k = 0; k < kBvhWidth; ++k) {
                const uint32_t slot = (order >> (2 * k)) & 3u;
                seen |= 1u << slot;
                if (k < used) {
                    EXPECT_LT(slot, used) << "node " << i << ": an unused slot before a used one";
                }
            }
            EXPECT_EQ(seen, 0xfu) << "node " << i << " octant " << octant << ": not a permutation";
        }
    }
    EXPECT_TRUE(binary_leaves.empty()) << binary_leaves.size() << " binary leaves missing from the wide tree";
    EXPECT_EQ(bvh.stats().wide_leaves, leaves);
    EXPECT_EQ(bvh.walk_steps(), wide.size() + leaves);
    EXPECT_LE(bvh.stats().stack_need, kBvhStackSize);
    EXPECT_LE(simulated_stack(wide), bvh.stats().stack_need);
    EXPECT_LE(bvh.stats().wide_depth, (bvh.stats().depth + 2) / 2);
}

// Checks the stackless layout against `kept` (the triangles that must be in it,
// 3 vertices each): pre-order with escapes, root escape -1, children inside
// parents, leaf counts 1..4, every triangle in exactly one leaf with its float
// vertices inside the leaf's box, and depth and counts as the stats report.
void expect_valid_layout(const ShadowBvh& bvh, const Triangles& kept) {
    const std::vector<GpuBvhNode>& nodes = bvh.gpu_nodes();
    const std::vector<GpuShadowTriangle>& tris = bvh.gpu_triangles();
    const size_t kept_count = kept.size() / 3;
    ASSERT_EQ(tris.size(), kept_count);
    ASSERT_EQ(bvh.stats().triangles, kept_count);
    ASSERT_EQ(bvh.stats().nodes, nodes.size());
    ASSERT_EQ(bvh.empty(), kept_count == 0);
    if (kept_count == 0) {
        EXPECT_TRUE(nodes.empty());
        return;
    }
    ASSERT_EQ(nodes[0].escape, kEndOfWalk);

    // The same triangles, as a multiset; then each one's original vertices.
    std::vector<std::pair<TriangleKey, size_t>> expected;
    expected.reserve(kept_count);
    for (size_t t = 0; t < kept_count; ++t)
        expected.emplace_back(key_of(kept[3 * t], kept[3 * t + 1], kept[3 * t + 2]), t);
    std::sort(expected.begin(), expected.end());
    std::vector<TriangleKey> actual;
    actual.reserve(kept_count);
    for (const GpuShadowTriangle& g : tris) {
        EXPECT_EQ(g.masked, 0u);  // opaque
        actual.push_back(key_of(g));
    }
    std::sort(actual.begin(), actual.end());
    for (size_t t = 0; t < kept_count; ++t)
        ASSERT_EQ(actual[t], expected[t].first) << "the BVH's triangles differ from the kept ones";

    struct Visit {
        size_t node;
        int64_t expected_escape;
        uint32_t depth;
        int64_t parent;
    };
    std::vector<uint8_t> node_seen(nodes.size(), 0);
    std::vector<uint8_t> triangle_seen(kept_count, 0);
    std::vector<Visit> stack{{0, kEndOfWalk, 0, -1}};
    uint32_t max_depth = 0;
    size_t visited = 0;
    while (!stack.empty()) {
        const Visit visit = stack.back();
        stack.pop_back();
        ASSERT_LT(visit.node, nodes.size());
        ASSERT_FALSE(node_seen[visit.node]) << "node " << visit.node << " reached twice";
        node_seen[visit.node] = 1;
        ++visited;
        const GpuBvhNode& node = nodes[visit.node];
        ASSERT_EQ(node.escape, visit.expected_escape) << "node " << visit.node;
        ASSERT_TRUE(node.escape == kEndOfWalk || node.escape > static_cast<int64_t>(visit.node));
        ASSERT_TRUE(node.bbox_min.x <= node.bbox_max.x && node.bbox_min.y <= node.bbox_max.y &&
                    node.bbox_min.z <= node.bbox_max.z);
        if (visit.parent >= 0) {
            const GpuBvhNode& parent = nodes[static_cast<size_t>(visit.parent)];
            EXPECT_TRUE(inside(node.bbox_min, parent.bbox_min, parent.bbox_max) &&
                        inside(node.bbox_max, parent.bbox_min, parent.bbox_max))
                << "node " << visit.node << " sticks out of its parent " << visit.parent;
        }
        max_depth = std::max(max_depth, visit.depth);
        if (node.triangles == 0) {
            // Inner: the left child follows; the right child is the left's escape
            // and ends the walk where the parent does.
            const size_t left = visit.node + 1;
            ASSERT_LT(left, nodes.size());
            const int64_t right = nodes[left].escape;
            ASSERT_GT(right, static_cast<int64_t>(left)) << "inner node " << visit.node;
            ASSERT_LT(right, static_cast<int64_t>(nodes.size()));
            if (node.escape != kEndOfWalk) {
                ASSERT_LT(right, node.escape);
            }
            const int64_t me = static_cast<int64_t>(visit.node);
            stack.push_back({static_cast<size_t>(right), node.escape, visit.depth + 1, me});
            stack.push_back({left, right, visit.depth + 1, me});
            continue;
        }
        const uint32_t first = node.triangles >> kBvhLeafCountBits;
        const uint32_t count = node.triangles & ((1u << kBvhLeafCountBits) - 1);
        ASSERT_GE(count, 1u);
        ASSERT_LE(count, kBvhMaxLeafSize);
        ASSERT_LE(size_t{first} + count, kept_count);
        for (uint32_t k = first; k < first + count; ++k) {
            ASSERT_FALSE(triangle_seen[k]) << "triangle " << k << " in two leaves";
            triangle_seen[k] = 1;
            const TriangleKey key = key_of(tris[k]);
            const auto found = std::lower_bound(
                expected.begin(), expected.end(), key,
                [](const std::pair<TriangleKey, size_t>& e, const TriangleKey& k2) { return e.first < k2; });
            ASSERT_TRUE(found != expected.end() && found->first == key);
            for (int v = 0; v < 3; ++v)
                ASSERT_TRUE(inside(kept[3 * found->second + v], node.bbox_min, node.bbox_max))
                    << "a vertex of triangle " << k << " lies outside leaf " << visit.node;
        }
    }
    EXPECT_EQ(visited, nodes.size()) << "nodes the tree does not reach";
    EXPECT_EQ(std::count(triangle_seen.begin(), triangle_seen.end(), 1),
              static_cast<std::ptrdiff_t>(kept_count));
    EXPECT_EQ(bvh.stats().depth, max_depth);
    expect_valid_wide_layout(bvh);
}

uint32_t log2_ceil(size_t n) {
    uint32_t bits = 0;
    while ((size_t{1} << bits) < n) ++bits;
    return bits;
}

// Two triangles making the axis-aligned square [x0, x1] x [y0, y1] at height z.
void add_square_xy(Triangles& tris, float x0, float x1, float y0, float y1, float z) {
    tris.insert(tris.end(), {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}});
    tris.insert(tris.end(), {{x0, y0, z}, {x1, y1, z}, {x0, y1, z}});
}

// --- Brute force agreement ----------------------------------------------------

TEST(ShadowBvhTest, RandomSoupsAgreeWithBruteForce) {
    const size_t kSizes[] = {1, 2, 5, 100, 5000};
    constexpr size_t kRays = 100000;
    for (const size_t size : kSizes) {
        SCOPED_TRACE(testing::Message() << size << " triangles");
        const double triangle_size = 1.6 / std::cbrt(static_cast<double>(size));
        const Triangles tris = random_soup(size, 1000 + size, glm::dvec3(0.0), 1.0, triangle_size);
        const ShadowBvh bvh = ShadowBvh::build(tris);
        expect_valid_layout(bvh, tris);
        EXPECT_EQ(bvh.stats().skipped_degenerate, 0u);
        const AgreementCounts counts =
            compare_with_brute_force(bvh, tris, kRays, 7 + size, glm::dvec3(-1.3), glm::dvec3(1.3));
        EXPECT_EQ(counts.disagreements, 0u);
        // Both answers occur often, and almost no ray is ambiguous.
        EXPECT_GT(counts.hits, kRays / 20);
        EXPECT_GT(counts.misses, kRays / 20);
        EXPECT_LT(counts.ambiguous, kRays / 1000);
        std::printf("[ soup %5zu ] hits %zu, misses %zu, ambiguous %zu; nodes %u, depth %u\n", size,
                    counts.hits, counts.misses, counts.ambiguous, bvh.stats().nodes, bvh.stats().depth);
    }
}

// Vertices and rays on a 1/4 grid: every quantity is exact, so rays graze
// edges, vertices and box faces exactly and no ray is ambiguous. Compared for
// every ray, with axis-parallel and diagonal directions.
TEST(ShadowBvhTest, GridAlignedScenesAgreeExactlyWithBruteForce) {
    Rng rng(4242);
    Triangles tris;
    auto grid = [&](double lo, double hi) { return std::round(rng.uniform(lo, hi) * 4.0) / 4.0; };
    for (int t = 0; t < 300; ++t) {
        const glm::dvec3 c(grid(-2, 2), grid(-2, 2), grid(-2, 2));
        for (int k = 0; k < 3; ++k) {
            glm::dvec3 v = c;
            // Flat in one random axis half the time: many boxes are flat, too.
            for (int a = 0; a < 3; ++a)
                if (!(t % 2 == 0 && a == t % 3)) v[a] += grid(-0.75, 0.75);
            tris.push_back(glm::vec3(v));
        }
    }
    const ShadowBvh bvh = ShadowBvh::build(tris);
    const Triangles kept = with_area(tris);
    EXPECT_EQ(bvh.stats().skipped_degenerate, (tris.size() - kept.size()) / 3);
    expect_valid_layout(bvh, kept);
    const BruteForce reference(kept);

    const glm::dvec3 kDirections[] = {{1, 0, 0}, {0, 1, 0},  {0, 0, 1}, {-1, 0, 0}, {0, 0, -1},
                                      {1, 1, 0}, {0, -1, 1}, {1, 1, 1}, {2, -1, 1}, {-1, 2, 4}};
    size_t hits = 0;
    size_t rays = 0;
    for (int r = 0; r < 40000; ++r) {
        const glm::dvec3 origin(grid(-3, 3), grid(-3, 3), grid(-3, 3));
        const glm::dvec3 direction = kDirections[rng.index(std::size(kDirections))];
        const Ray ray{origin, direction, static_cast<double>(1 + rng.index(8)) * 0.5};
        const bool want = reference.occluded(ray);
        hits += want;
        ++rays;
        ASSERT_EQ(bvh.occluded(ray.origin, ray.direction, ray.t_max), want)
            << "origin (" << origin.x << ", " << origin.y << ", " << origin.z << ") direction ("
            << direction.x << ", " << direction.y << ", " << direction.z << ") t_max " << ray.t_max;
    }
    EXPECT_GT(hits, rays / 20);
    EXPECT_LT(hits, rays - rays / 20);
}

// --- Hard cases ---------------------------------------------------------------

TEST(ShadowBvhTest, EmptyInputGivesAnEmptyBvhThatOccludesNothing) {
    const ShadowBvh from_span = ShadowBvh::build(std::span<const glm::vec3>());
    EXPECT_TRUE(from_span.empty());
    EXPECT_TRUE(from_span.gpu_nodes().empty());
    EXPECT_TRUE(from_span.gpu_triangles().empty());
    EXPECT_EQ(from_span.stats().triangles, 0u);
    EXPECT_EQ(from_span.stats().nodes, 0u);
    EXPECT_EQ(from_span.stats().depth, 0u);
    EXPECT_FALSE(from_span.occluded({0, 0, 0}, {0, 0, 1}, kInf));

    const ShadowBvh from_scene = ShadowBvh::build(Scene{});
    EXPECT_TRUE(from_scene.empty());
    EXPECT_FALSE(from_scene.occluded({0, 0, 0}, {1, 0, 0}, 10.0));

    const ShadowBvh default_constructed;
    EXPECT_TRUE(default_constructed.empty());
    EXPECT_FALSE(default_constructed.occluded({0, 0, 0}, {1, 0, 0}, 10.0));
}

TEST(ShadowBvhTest, OneTriangleIsOneLeaf) {
    const Triangles tris = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
    const ShadowBvh bvh = ShadowBvh::build(tris);
    expect_valid_layout(bvh, tris);
    ASSERT_EQ(bvh.gpu_nodes().size(), 1u);
    EXPECT_EQ(bvh.gpu_nodes()[0].escape, kEndOfWalk);
    EXPECT_EQ(bvh.gpu_nodes()[0].triangles, (0u << kBvhLeafCountBits) | 1u);
    EXPECT_EQ(bvh.stats().depth, 0u);
    EXPECT_EQ(bvh.gpu_triangles()[0].v0, glm::vec3(0, 0, 1));
    EXPECT_EQ(bvh.gpu_triangles()[0].edge1, glm::vec3(1, 0, 0));
    EXPECT_EQ(bvh.gpu_triangles()[0].edge2, glm::vec3(0, 1, 0));

    EXPECT_TRUE(bvh.occluded({0.25, 0.25, 0}, {0, 0, 1}, 2.0));
    EXPECT_TRUE(bvh.occluded({0.25, 0.25, 2}, {0, 0, -1}, 2.0));  // the back face too
    EXPECT_TRUE(bvh.occluded({0.25, 0.25, 0}, {0, 0, 1}, kInf));
    EXPECT_FALSE(bvh.occluded({0.75, 0.75, 0}, {0, 0, 1}, 2.0));  // beside the hypotenuse
    EXPECT_FALSE(bvh.occluded({0.25, 0.25, 0}, {0, 0, 1}, 0.5));  // stops short
    // Unnormalized direction: t in its units.
    EXPECT_TRUE(bvh.occluded({0.25, 0.25, 0}, {0, 0, 4}, 0.3));
    EXPECT_FALSE(bvh.occluded({0.25, 0.25, 0}, {0, 0, 4}, 0.2));
}

TEST(ShadowBvhTest, HitsExactlyAtTheEndsOrBehindTheOriginDoNotCount) {
    const Triangles tris = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
    const ShadowBvh bvh = ShadowBvh::build(tris);
    // t = 1 exactly: 0 < t < t_max is strict.
    EXPECT_FALSE(bvh.occluded({0.25, 0.25, 0}, {0, 0, 1}, 1.0));
    EXPECT_TRUE(bvh.occluded({0.25, 0.25, 0}, {0, 0, 1}, std::nextafter(1.0, 2.0)));
    // Behind the origin.
    EXPECT_FALSE(bvh.occluded({0.25, 0.25, 0}, {0, 0, -1}, kInf));
    EXPECT_FALSE(bvh.occluded({0.25, 0.25, 3}, {0, 0, 1}, kInf));
    // Starting on the triangle: t = 0 is not a hit, either way.
    EXPECT_FALSE(bvh.occluded({0.25, 0.25, 1}, {0, 0, 1}, kInf));
    EXPECT_FALSE(bvh.occluded({0.25, 0.25, 1}, {0, 0, -1}, kInf));
    // Just off it, towards it.
    EXPECT_TRUE(bvh.occluded({0.25, 0.25, std::nextafter(1.0, 0.0)}, {0, 0, 1}, kInf));
    // Nonsense rays answer "not occluded", never crash.
    EXPECT_FALSE(bvh.occluded({0.25, 0.25, 0}, {0, 0, 1}, 0.0));
    EXPECT_FALSE(bvh.occluded({0.25, 0.25, 0}, {0, 0, 1}, -1.0));
    EXPECT_FALSE(bvh.occluded({0.25, 0.25, 0}, {0, 0, 1}, std::nan("")));
    EXPECT_FALSE(bvh.occluded({0.25, 0.25, 0}, {0, 0, 0}, 2.0));
    EXPECT_FALSE(bvh.occluded({std::nan(""), 0.25, 0}, {0, 0, 1}, 2.0));
    EXPECT_FALSE(bvh.occluded({0.25, 0.25, 0}, {0, kInf, 1}, 2.0));
    // A denormal direction component (1 / d overflows) on a box face still works.
    EXPECT_TRUE(bvh.occluded({0.25, 0.25, 0}, {4.9e-324, 0, 1}, 2.0));
}

TEST(ShadowBvhTest, AxisParallelRaysHitAndGrazeBoxFaces) {
    // A unit square at z = 0 and a wall at x = 2 (a flat box each).
    Triangles tris;
    add_square_xy(tris, 0, 1, 0, 1, 0);
    tris.insert(tris.end(), {{2, 0, 0}, {2, 1, 0}, {2, 0, 1}});
    const ShadowBvh bvh = ShadowBvh::build(tris);
    expect_valid_layout(bvh, tris);

    // Straight down onto the square: inside, on its edges and corners (hits),
    // and the smallest step outside (misses).
    const double below = std::nextafter(0.0, -1.0);
    const double above = std::nextafter(1.0, 2.0);
    const std::pair<glm::dvec2, bool> kPoints[] = {
        {{0.5, 0.5}, true},      {{0.0, 0.5}, true},    {{1.0, 0.5}, true},    {{0.5, 0.0}, true},
        {{0.5, 1.0}, true},      {{0.0, 0.0}, true},    {{1.0, 1.0}, true},    {{0.0, 1.0}, true},
        {{below, 0.5}, false},   {{above, 0.5}, false}, {{0.5, below}, false}, {{0.5, above}, false},
        {{below, below}, false}, {{-1.0, 0.5}, false},
    };
    for (const auto& [p, want] : kPoints) {
        SCOPED_TRACE(testing::Message() << "at (" << p.x << ", " << p.y << ")");
        EXPECT_EQ(bvh.occluded({p.x, p.y, -1.0}, {0, 0, 1}, 2.0), want);
        EXPECT_EQ(bvh.occluded({p.x, p.y, 1.0}, {0, 0, -1}, 2.0), want);
        EXPECT_EQ(bvh.occluded({p.x, p.y, 1.0}, {0, 0, -1}, 1.0), false);  // ends on it
    }
    // Along x through the wall at x = 2, on its edges y = 0 and z = 0, and past them.
    EXPECT_TRUE(bvh.occluded({3, 0.25, 0.25}, {-1, 0, 0}, 5.0));
    EXPECT_TRUE(bvh.occluded({3, 0.0, 0.25}, {-1, 0, 0}, 5.0));
    EXPECT_TRUE(bvh.occluded({3, 0.25, 0.0}, {-1, 0, 0}, 5.0));
    EXPECT_FALSE(bvh.occluded({3, 0.25, 0.25}, {-1, 0, 0}, 0.5));  // stops before the wall
    // The smallest step below the wall's edge z = 0 (and parallel to the square).
    EXPECT_FALSE(bvh.occluded({3, 0.25, below}, {-1, 0, 0}, 5.0));
    EXPECT_FALSE(bvh.occluded({3, below, 0.25}, {-1, 0, 0}, 5.0));
    // In the plane of the square (det = 0 for it), along x: nothing to hit before the wall.
    EXPECT_FALSE(bvh.occluded({-1, 0.5, 0}, {1, 0, 0}, 2.9));
    // Origins exactly on the root box's (one-ulp-widened) faces, moving parallel
    // to them: the slab is 0 * inf there, which must not make a hit vanish.
    const GpuBvhNode& root = bvh.gpu_nodes()[0];
    EXPECT_TRUE(bvh.occluded({2.5, 0.25, root.bbox_min.z}, {-1, 0, 1e-3}, 5.0));
    EXPECT_FALSE(bvh.occluded({root.bbox_min.x, 0.5, -1}, {0, 0, 1}, 2.0));
    EXPECT_FALSE(bvh.occluded({0.5, root.bbox_max.y, -1}, {0, 0, 1}, 2.0));
}

TEST(ShadowBvhTest, RaysStartingInsideBoxes) {
    // A closed cube of 12 triangles, spanning [-1, 1]^3.
    Triangles tris;
    for (int axis = 0; axis < 3; ++axis) {
        for (const float side : {-1.0f, 1.0f}) {
            const glm::vec3 corners[4] = {{-1, -1, side}, {1, -1, side}, {1, 1, side}, {-1, 1, side}};
            glm::vec3 rotated[4];
            for (int k = 0; k < 4; ++k) {
                // Move the fixed coordinate (z) onto `axis`.
                const glm::vec3 c = corners[k];
                rotated[k] = axis == 2 ? c : axis == 0 ? glm::vec3(c.z, c.x, c.y) : glm::vec3(c.y, c.z, c.x);
            }
            tris.insert(tris.end(), {rotated[0], rotated[1], rotated[2]});
            tris.insert(tris.end(), {rotated[0], rotated[2], rotated[3]});
        }
    }
    // And a small cluster inside it, whose leaf boxes contain the ray origins below.
    const Triangles inner = random_soup(40, 5, glm::dvec3(0.0), 0.3, 0.1);
    tris.insert(tris.end(), inner.begin(), inner.end());
    const ShadowBvh bvh = ShadowBvh::build(tris);
    expect_valid_layout(bvh, tris);
    const BruteForce reference(tris);

    Rng rng(99);
    for (int r = 0; r < 2000; ++r) {
        const glm::dvec3 origin = rng.point(glm::dvec3(-0.9), glm::dvec3(0.9));
        glm::dvec3 direction = rng.point(glm::dvec3(-1), glm::dvec3(1));
        if (r % 3 == 0) direction = glm::dvec3(0.0, 0.0, r % 2 == 0 ? 1.0 : -1.0);
        // Long enough to leave the cube: always blocked, by the walls at least.
        EXPECT_TRUE(bvh.occluded(origin, direction, 100.0 / glm::length(direction)));
        const Ray ray{origin, direction, 0.05 / glm::length(direction)};
        const Reference want = reference.classify(ray);
        if (want != Reference::kAmbiguous) {
            EXPECT_EQ(bvh.occluded(ray.origin, ray.direction, ray.t_max), want == Reference::kHit);
        }
    }
}

TEST(ShadowBvhTest, IdenticalTrianglesBuildABalancedTree) {
    constexpr size_t kCount = 100000;
    Triangles tris;
    tris.reserve(3 * kCount);
    for (size_t i = 0; i < kCount; ++i) tris.insert(tris.end(), {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const ShadowBvh bvh = ShadowBvh::build(tris);
    expect_valid_layout(bvh, tris);
    // Median splits halve the range: ceil(log2(count / 4)) levels.
    EXPECT_LE(bvh.stats().depth, log2_ceil(kCount / kBvhMaxLeafSize) + 1);
    EXPECT_TRUE(bvh.occluded({0.2, 0.2, -1}, {0, 0, 1}, 2.0));
    EXPECT_FALSE(bvh.occluded({0.8, 0.8, -1}, {0, 0, 1}, 2.0));
    EXPECT_FALSE(bvh.occluded({0.2, 0.2, -1}, {0, 0, 1}, 0.5));
}

// Triangles facing +x at x = first * ratio^i, i < count, of size
// size_fraction * x: the depth stays within max_depth and rays along the
// chain agree with brute force.
void expect_geometric_chain_ok(size_t count, double first, double ratio, double size_fraction,
                               uint32_t max_depth) {
    SCOPED_TRACE(testing::Message() << "chain x = " << first << " * " << ratio << "^i");
    Triangles tris;
    double x = first;
    for (size_t i = 0; i < count; ++i, x *= ratio) {
        const float s = static_cast<float>(size_fraction * x);
        const float xf = static_cast<float>(x);
        tris.insert(tris.end(), {{xf, -s, -s}, {xf, s, -s}, {xf, 0.0f, s}});
    }
    const ShadowBvh bvh = ShadowBvh::build(tris);
    expect_valid_layout(bvh, tris);
    EXPECT_LE(bvh.stats().depth, max_depth);
    std::printf("[ chain ] %zu geometrically spaced (ratio %g): depth %u, nodes %u\n", count, ratio,
                bvh.stats().depth, bvh.stats().nodes);
    // From just before a triangle, towards +x, ending before or after it.
    const BruteForce reference(tris);
    Rng rng(3);
    size_t hits = 0;
    for (int r = 0; r < 2000; ++r) {
        const double xi = tris[3 * rng.index(count)].x;
        const double s = size_fraction * xi;
        const Ray ray{
            {xi * 0.99, rng.uniform(-s, s), rng.uniform(-s, s)}, {1, 0, 0}, rng.uniform(0.0, 0.02) * xi};
        const Reference want = reference.classify(ray);
        hits += want == Reference::kHit;
        if (want != Reference::kAmbiguous) {
            EXPECT_EQ(bvh.occluded(ray.origin, ray.direction, ray.t_max), want == Reference::kHit);
        }
    }
    EXPECT_GT(hits, 200u);
    EXPECT_LT(hits, 1800u);
}

TEST(ShadowBvhTest, ChainsAlongALineKeepAReasonableDepth) {
    // Evenly spaced: SAH splits it evenly.
    {
        constexpr size_t kCount = 20000;
        Triangles tris;
        for (size_t i = 0; i < kCount; ++i) {
            const float x = static_cast<float>(i) * 0.01f;
            tris.insert(tris.end(), {{x, -0.1f, -0.1f}, {x, 0.1f, -0.1f}, {x, 0.0f, 0.1f}});
        }
        const ShadowBvh bvh = ShadowBvh::build(tris);
        expect_valid_layout(bvh, tris);
        EXPECT_LE(bvh.stats().depth, 2 * log2_ceil(kCount));
        std::printf("[ chain ] %zu evenly spaced: depth %u, nodes %u\n", kCount, bvh.stats().depth,
                    bvh.stats().nodes);
        // Along the chain: the first wall blocks; beside it nothing does.
        EXPECT_TRUE(bvh.occluded({-1, 0, 0}, {1, 0, 0}, kInf));
        EXPECT_FALSE(bvh.occluded({-1, 0.5, 0}, {1, 0, 0}, kInf));
        EXPECT_FALSE(bvh.occluded({100.005, 0, 0}, {0, 0, 1}, kInf));
        EXPECT_TRUE(bvh.occluded({100.005, 0, 0}, {1, 0, 0}, 0.01));
        EXPECT_FALSE(bvh.occluded({100.005, 0, 0}, {1, 0, 0}, 0.004));
    }
    // Geometrically spaced, with sizes in proportion: 16 uniform bins put all
    // but the last few triangles in the first bin. x = 1.1^i: SAH peels some
    // 30 triangles per level. x = 2^(124 - 3i), size x / 4: SAH alone peels
    // one per level (depth 78 for 82 triangles); the median fallback past
    // depth 48 must bound it.
    expect_geometric_chain_ok(900, 1.0, 1.1, 0.01, 64);
    expect_geometric_chain_ok(82, 0x1p124, 0.125, 0.25, 48 + log2_ceil(82) + 1);
}

// The 82-triangle chain peels one triangle per level: with SAH to depth 48
// its wide walk would need more than kBvhStackSize entries, so the build
// lowers the SAH depth until it fits.
TEST(ShadowBvhTest, DeepChainsLowerTheSahDepthToFitTheStack) {
    Triangles tris;
    double x = 0x1p124;
    for (size_t i = 0; i < 82; ++i, x *= 0.125) {
        const float s = static_cast<float>(0.25 * x);
        const float xf = static_cast<float>(x);
        tris.insert(tris.end(), {{xf, -s, -s}, {xf, s, -s}, {xf, 0.0f, s}});
    }
    const ShadowBvh bvh = ShadowBvh::build(tris);
    expect_valid_layout(bvh, tris);
    EXPECT_LT(bvh.stats().max_sah_depth, 48u);
    EXPECT_LE(bvh.stats().stack_need, kBvhStackSize);
    std::printf("[ chain 82 ] SAH to depth %u: depth %u, wide depth %u, stack %u\n", bvh.stats().max_sah_depth,
                bvh.stats().depth, bvh.stats().wide_depth, bvh.stats().stack_need);
}

// Four squares in a row along x, 2 apart: the root has them as its four
// slots, ordered by x for +x rays and backwards for -x rays.
TEST(ShadowBvhTest, WideNodesOrderTheirChildrenNearestFirst) {
    Triangles tris;
    for (int k = 0; k < 4; ++k) {
        const float x0 = 2.0f * float(k);
        add_square_xy(tris, x0, x0 + 1.0f, 0.0f, 1.0f, 0.0f);
        add_square_xy(tris, x0, x0 + 1.0f, 0.0f, 1.0f, 0.5f);
    }
    const ShadowBvh bvh = ShadowBvh::build(tris);
    expect_valid_layout(bvh, tris);
    ASSERT_EQ(bvh.gpu_wide_nodes().size(), 1u);
    const GpuWideBvhNode& root = bvh.gpu_wide_nodes()[0];
    auto slot_x = [&](uint32_t order, uint32_t k) { return root.lo_x[int((order >> (2 * k)) & 3u)]; };
    for (uint32_t octant = 0; octant < 8; ++octant) {
        const uint32_t order = slot_order(root, octant);
        for (uint32_t k = 0; k + 1 < kBvhWidth; ++k) {
            if (octant & 1u) {
                EXPECT_GT(slot_x(order, k), slot_x(order, k + 1)) << "octant " << octant;
            } else {
                EXPECT_LT(slot_x(order, k), slot_x(order, k + 1)) << "octant " << octant;
            }
        }
    }
    EXPECT_TRUE(bvh.occluded({-1, 0.5, 0.25}, {1, 0, 0}, kInf) == false);
    EXPECT_TRUE(bvh.occluded({0.5, 0.5, -1}, {0, 0, 1}, kInf));
    EXPECT_TRUE(bvh.occluded({6.5, 0.5, 1}, {0, 0, -1}, 0.6));
    EXPECT_FALSE(bvh.occluded({6.5, 0.5, 1}, {0, 0, -1}, 0.4));
}

// The parallel build's nodes, triangles and sources, byte for byte, on one
// thread and on all (ranges past the parallel grain split into tasks).
TEST(ShadowBvhTest, BuildIsTheSameAtAnyThreadCount) {
    const Triangles tris = random_soup(60000, 77, glm::dvec3(0.0), 1.0, 0.05);
    // All the threads TBB offers (two on a two-core box) against one.
    auto build_on = [&](int threads) {
        tbb::task_arena arena(threads);
        ShadowBvh bvh;
        arena.execute([&] { bvh = ShadowBvh::build(tris); });
        return bvh;
    };
    const ShadowBvh one = build_on(1);
    const ShadowBvh all = build_on(std::max(2, tbb::info::default_concurrency()));
    expect_valid_layout(one, tris);
    auto same_bytes = [](const auto& a, const auto& b) {
        return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
    };
    EXPECT_TRUE(same_bytes(one.gpu_nodes(), all.gpu_nodes()));
    EXPECT_TRUE(same_bytes(one.gpu_wide_nodes(), all.gpu_wide_nodes()));
    EXPECT_TRUE(same_bytes(one.gpu_triangles(), all.gpu_triangles()));
    EXPECT_TRUE(same_bytes(one.leaf_sources(), all.leaf_sources()));
    EXPECT_GT(one.stats().wide_nodes, 60000u / 16);
}

// Two clusters, 30 triangles at x in [0, 1] and 70 at x in [9, 10]: the SAH
// root split separates them (an object median would put 20 of the 70 on the
// left).
TEST(ShadowBvhTest, SahSeparatesClusters) {
    Triangles tris = random_soup(30, 61, glm::dvec3(0.5, 0.5, 0.5), 0.4, 0.05);
    const Triangles far_cluster = random_soup(70, 62, glm::dvec3(9.5, 0.5, 0.5), 0.4, 0.05);
    tris.insert(tris.end(), far_cluster.begin(), far_cluster.end());
    const ShadowBvh bvh = ShadowBvh::build(tris);
    expect_valid_layout(bvh, tris);
    const std::vector<GpuBvhNode>& nodes = bvh.gpu_nodes();
    ASSERT_EQ(nodes[0].triangles, 0u);
    const size_t left = 1;
    const size_t right = static_cast<size_t>(nodes[left].escape);
    auto triangles_in = [&](size_t begin, size_t end) {
        uint32_t n = 0;
        for (size_t i = begin; i < end; ++i) n += nodes[i].triangles & ((1u << kBvhLeafCountBits) - 1);
        return n;
    };
    EXPECT_EQ(triangles_in(left, right), 30u);
    EXPECT_EQ(triangles_in(right, nodes.size()), 70u);
    EXPECT_LT(nodes[left].bbox_max.x, 2.0f);
    EXPECT_GT(nodes[right].bbox_min.x, 8.0f);
}

TEST(ShadowBvhTest, FarFromTheOriginAndSmall) {
    // Around 1e6 the float spacing is 1/16: triangles of 1 to 8 units span
    // 16-128 float steps, and the double answers still agree with brute force.
    {
        const glm::dvec3 center(1e6, -1e6, 1e6);
        const Triangles tris = random_soup(2000, 17, center, 40.0, 2.0);
        const ShadowBvh bvh = ShadowBvh::build(tris);
        expect_valid_layout(bvh, tris);
        EXPECT_EQ(bvh.stats().skipped_degenerate, 0u);
        const AgreementCounts counts =
            compare_with_brute_force(bvh, tris, 20000, 23, center - 45.0, center + 45.0);
        EXPECT_EQ(counts.disagreements, 0u);
        EXPECT_GT(counts.hits, 1000u);
        EXPECT_GT(counts.misses, 1000u);
    }
    // 1e-3 triangles around 1e3 (float spacing 6e-5: 16 steps per triangle).
    {
        const glm::dvec3 center(1e3, 1e3, -1e3);
        const Triangles tris = random_soup(2000, 19, center, 0.02, 1e-3);
        const ShadowBvh bvh = ShadowBvh::build(tris);
        const Triangles kept = with_area(tris);
        expect_valid_layout(bvh, kept);
        EXPECT_GT(kept.size(), tris.size() * 9 / 10);
        const AgreementCounts counts =
            compare_with_brute_force(bvh, kept, 20000, 29, center - 0.025, center + 0.025);
        EXPECT_EQ(counts.disagreements, 0u);
        EXPECT_GT(counts.hits, 1000u);
        EXPECT_GT(counts.misses, 1000u);
    }
    // 1e-3 triangles at 1e6 cannot exist in float (every vertex rounds to the
    // same or a collinear point): they are all skipped as degenerate, no crash.
    {
        const glm::dvec3 center(1e6, 1e6, 1e6);
        const Triangles tris = random_soup(500, 31, center, 0.01, 1e-3);
        const ShadowBvh bvh = ShadowBvh::build(tris);
        const Triangles kept = with_area(tris);
        expect_valid_layout(bvh, kept);
        EXPECT_EQ(bvh.stats().skipped_degenerate + bvh.stats().triangles, 500u);
        EXPECT_GT(bvh.stats().skipped_degenerate, 400u);
        EXPECT_FALSE(bvh.occluded(center + glm::dvec3(0, 0, -1), {0, 0, 1}, 0.5));
    }
}

TEST(ShadowBvhTest, DegenerateAndNonFiniteTrianglesAreSkipped) {
    const float nan = kFloatNaN;
    const float inf = kFloatInf;
    const Triangles good = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
    Triangles tris = {
        {0, 0, 0},   {0, 0, 0},   {0, 0, 0},     // a point
        {0, 0, 0},   {1, 1, 1},   {2, 2, 2},     // collinear
        {0, 0, 0},   {1, 0, 0},   {1, 0, 0},     // a repeated vertex
        {nan, 0, 0}, {1, 0, 0},   {0, 1, 0},     // NaN
        {0, 0, 0},   {inf, 0, 0}, {0, 1, 0},     // inf
        {0, 0, 0},   {1, 0, 0},   {0, -inf, 0},  // -inf
    };
    tris.insert(tris.end(), good.begin(), good.end());
    tris.insert(tris.end(), {{5, 5, 5}, {6, 5, 5}});  // a trailing partial triangle
    const ShadowBvh bvh = ShadowBvh::build(tris);
    EXPECT_EQ(bvh.stats().skipped_degenerate, 7u);
    EXPECT_EQ(bvh.stats().triangles, 1u);
    expect_valid_layout(bvh, good);
    EXPECT_TRUE(bvh.occluded({0.25, 0.25, 0}, {0, 0, 1}, 2.0));
    EXPECT_FALSE(bvh.occluded({0.5, 0.5, -1}, {1, 1, 1}, 0.75));  // through the collinear one

    // Only bad triangles: an empty BVH, counted.
    const Triangles bad(tris.begin(), tris.begin() + 18);
    const ShadowBvh none = ShadowBvh::build(bad);
    EXPECT_TRUE(none.empty());
    EXPECT_EQ(none.stats().skipped_degenerate, 6u);
    EXPECT_FALSE(none.occluded({0, 0, -1}, {0, 0, 1}, kInf));

    // Huge but finite coordinates (float max): kept, boxes stay finite.
    const float big = std::numeric_limits<float>::max();
    const Triangles huge = {{-big, -big, 0}, {big, -big, 0}, {0, big, 0}};
    const ShadowBvh wide = ShadowBvh::build(huge);
    expect_valid_layout(wide, huge);
    EXPECT_TRUE(std::isfinite(wide.gpu_nodes()[0].bbox_min.x));
    EXPECT_TRUE(std::isfinite(wide.gpu_nodes()[0].bbox_max.y));
    EXPECT_TRUE(wide.occluded({0, 0, -1}, {0, 0, 1}, 2.0));
    EXPECT_FALSE(wide.occluded({0, 0, -1}, {0, 0, -1}, 2.0));
}

// --- Scenes and materials -------------------------------------------------------

Mesh mesh_of(const Triangles& tris, int material) {
    Mesh mesh;
    mesh.positions = tris;
    for (uint32_t i = 0; i < tris.size(); ++i) mesh.indices.push_back(i);
    mesh.material = material;
    return mesh;
}

TEST(ShadowBvhTest, OnlyShadowCastingMaterialsOcclude) {
    Scene scene;
    scene.materials.resize(2);
    scene.materials[1].casts_shadows = false;  // glass
    Triangles floor_tris;
    add_square_xy(floor_tris, 0, 1, 0, 1, 0);
    Triangles glass_tris;
    add_square_xy(glass_tris, 0, 1, 0, 1, 1);
    Triangles default_tris;
    add_square_xy(default_tris, 2, 3, 0, 1, 1);
    Triangles out_of_range_tris;
    add_square_xy(out_of_range_tris, 4, 5, 0, 1, 1);
    scene.meshes.push_back(mesh_of(floor_tris, 0));
    scene.meshes.push_back(mesh_of(glass_tris, 1));
    scene.meshes.push_back(mesh_of(default_tris, -1));      // glTF's default material casts
    scene.meshes.push_back(mesh_of(out_of_range_tris, 7));  // out of range: the default too
    // A mesh with an index out of range and a trailing partial triple.
    Mesh broken = mesh_of(default_tris, -1);
    broken.indices = {0, 1, 2, 0, 1, 99, 3, 4};
    scene.meshes.push_back(broken);

    const ShadowBvh bvh = ShadowBvh::build(scene);
    EXPECT_EQ(bvh.stats().skipped_non_casting, 2u);
    EXPECT_EQ(bvh.stats().skipped_degenerate, 2u);
    EXPECT_EQ(bvh.stats().triangles, 7u);
    Triangles kept = floor_tris;
    kept.insert(kept.end(), default_tris.begin(), default_tris.end());
    kept.insert(kept.end(), out_of_range_tris.begin(), out_of_range_tris.end());
    kept.insert(kept.end(), default_tris.begin(), default_tris.begin() + 3);
    expect_valid_layout(bvh, kept);

    // From above the glass, down to just over the floor: the glass does not block.
    EXPECT_FALSE(bvh.occluded({0.5, 0.5, 2}, {0, 0, -1}, 1.5));
    EXPECT_TRUE(bvh.occluded({0.5, 0.5, 2}, {0, 0, -1}, 2.5));  // the floor does
    EXPECT_TRUE(bvh.occluded({2.5, 0.5, 2}, {0, 0, -1}, 1.5));
    EXPECT_TRUE(bvh.occluded({4.5, 0.5, 2}, {0, 0, -1}, 1.5));

    // Nothing casts: an empty BVH.
    Scene glass_only;
    glass_only.materials.resize(1);
    glass_only.materials[0].casts_shadows = false;
    glass_only.meshes.push_back(mesh_of(glass_tris, 0));
    const ShadowBvh none = ShadowBvh::build(glass_only);
    EXPECT_TRUE(none.empty());
    EXPECT_EQ(none.stats().skipped_non_casting, 2u);
    EXPECT_FALSE(none.occluded({0.5, 0.5, 2}, {0, 0, -1}, 10.0));
}

// --- Determinism and scale ------------------------------------------------------

template <typename T>
bool same_bytes(const std::vector<T>& a, const std::vector<T>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0;
}

TEST(ShadowBvhTest, BuildsAreByteIdentical) {
    const Triangles tris = random_soup(5000, 77, glm::dvec3(0.0), 1.0, 0.05);
    const ShadowBvh first = ShadowBvh::build(tris);
    const ShadowBvh second = ShadowBvh::build(tris);
    ASSERT_FALSE(first.empty());
    EXPECT_TRUE(same_bytes(first.gpu_nodes(), second.gpu_nodes()));
    EXPECT_TRUE(same_bytes(first.gpu_triangles(), second.gpu_triangles()));

    Scene scene;
    scene.meshes.push_back(mesh_of(tris, -1));
    scene.meshes.push_back(mesh_of(random_soup(300, 78, glm::dvec3(2.0), 0.5, 0.05), -1));
    const ShadowBvh from_scene = ShadowBvh::build(scene);
    const ShadowBvh again = ShadowBvh::build(scene);
    EXPECT_TRUE(same_bytes(from_scene.gpu_nodes(), again.gpu_nodes()));
    EXPECT_TRUE(same_bytes(from_scene.gpu_triangles(), again.gpu_triangles()));
    EXPECT_EQ(from_scene.stats().triangles, 5300u);
}

// The walk the shaders do (shaders/shadow_rays.glsl), in float, over the
// uploaded buffers alone: against a float loop over the same triangles, it
// must never lose a hit to its box tests (the one-ulp widening and the far
// distance's slack cover float rounding). A few disagreements from the
// float triangle test itself near edges are possible only in the reference,
// not here: both sides use the same float triangle test.
bool float_ray_hits_triangle(const glm::vec3& origin, const glm::vec3& direction, float t_max,
                             const GpuShadowTriangle& tri) {
    const glm::vec3 p = glm::cross(direction, tri.edge2);
    const float det = glm::dot(tri.edge1, p);
    if (det == 0.0f) return false;
    const float inv_det = 1.0f / det;
    const glm::vec3 s = origin - tri.v0;
    const float u = glm::dot(s, p) * inv_det;
    const glm::vec3 q = glm::cross(s, tri.edge1);
    const float v = glm::dot(direction, q) * inv_det;
    const float t = glm::dot(tri.edge2, q) * inv_det;
    return u >= 0.0f && v >= 0.0f && u + v <= 1.0f && t > 0.0f && t < t_max;
}

// The shaders' slab test of one wide slot, in float.
bool float_ray_hits_slot(const glm::vec3& origin, const glm::vec3& inv, float t_max, const GpuWideBvhNode& node,
                         int slot) {
    const glm::vec3 lo(node.lo_x[slot], node.lo_y[slot], node.lo_z[slot]);
    const glm::vec3 hi(node.hi_x[slot], node.hi_y[slot], node.hi_z[slot]);
    const glm::vec3 t0 = (lo - origin) * inv;
    const glm::vec3 t1 = (hi - origin) * inv;
    const glm::vec3 near = glm::min(t0, t1);
    const glm::vec3 far = glm::max(t0, t1);
    const float enter = std::max(std::max(near.x, near.y), std::max(near.z, 0.0f));
    const float leave = std::min(std::min(far.x, far.y), std::min(far.z, t_max)) * 1.000001f;
    return enter <= leave;
}

// The 4-wide walk with its stack of kBvhStackSize entries, nearest-first.
bool float_walk(const ShadowBvh& bvh, const glm::vec3& origin, const glm::vec3& direction, float t_max) {
    glm::vec3 safe = direction;
    for (int a = 0; a < 3; ++a)
        if (safe[a] == 0.0f) safe[a] = 1e-30f;
    const glm::vec3 inv = 1.0f / safe;
    const auto& nodes = bvh.gpu_wide_nodes();
    if (nodes.empty()) return false;
    const uint32_t octant = direction_octant(direction.x < 0.0f, direction.y < 0.0f, direction.z < 0.0f);
    std::array<uint32_t, kBvhStackSize> stack{};
    size_t size = 0;
    uint32_t entry = 0;
    for (;;) {
        const uint32_t count = entry & kBvhLeafCountMask;
        const uint32_t index = entry >> kBvhLeafCountBits;
        if (count == 0) {
            const GpuWideBvhNode& node = nodes[index];
            const uint32_t order = slot_order(node, octant);
            for (uint32_t k = kBvhWidth; k-- > 0;) {
                const int slot = int((order >> (2 * k)) & 3u);
                if (node.children[slot] == kBvhEmptyChild) continue;
                if (!float_ray_hits_slot(origin, inv, t_max, node, slot)) continue;
                EXPECT_LT(size, kBvhStackSize);
                if (size == kBvhStackSize) return false;
                stack[size++] = node.children[slot];
            }
        } else {
            for (uint32_t k = 0; k < count; ++k)
                if (float_ray_hits_triangle(origin, direction, t_max, bvh.gpu_triangles()[index + k])) return true;
        }
        if (size == 0) return false;
        entry = stack[--size];
    }
}

TEST(ShadowBvhTest, FloatWalkOverTheUploadedBuffersLosesNoHit) {
    const Triangles tris = random_soup(5000, 1234, glm::dvec3(0.0), 1.0, 0.05);
    const ShadowBvh bvh = ShadowBvh::build(tris);
    Rng rng(5678);
    size_t hits = 0;
    size_t lost = 0;
    constexpr size_t kRays = 10000;
    for (size_t r = 0; r < kRays; ++r) {
        const Ray ray = random_ray(rng, tris, glm::dvec3(-1.3), glm::dvec3(1.3));
        const glm::vec3 origin(ray.origin);
        const glm::vec3 direction(ray.direction);
        const float t_max = static_cast<float>(ray.t_max);
        bool want = false;
        for (const GpuShadowTriangle& g : bvh.gpu_triangles())
            if (float_ray_hits_triangle(origin, direction, t_max, g)) {
                want = true;
                break;
            }
        hits += want;
        if (want && !float_walk(bvh, origin, direction, t_max)) ++lost;
        if (!want) {
            EXPECT_FALSE(float_walk(bvh, origin, direction, t_max));
        }
    }
    std::printf("[ float walk ] %zu rays, %zu hits, %zu lost by the box tests\n", kRays, hits, lost);
    EXPECT_GT(hits, kRays / 10);
    EXPECT_EQ(lost, 0u);
}

TEST(ShadowBvhTest, AMillionTrianglesBuildAndAnswer) {
    constexpr size_t kCount = 1000000;
    const Triangles tris = random_soup(kCount, 2024, glm::dvec3(0.0), 10.0, 0.03);
    const auto start = std::chrono::steady_clock::now();
    const ShadowBvh bvh = ShadowBvh::build(tris);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::printf("[ scale ] %zu triangles: build %.3f s, %u nodes, depth %u\n", kCount, seconds,
                bvh.stats().nodes, bvh.stats().depth);
    expect_valid_layout(bvh, tris);
    EXPECT_LE(bvh.stats().depth, 64u);

    // A few dozen segments against the brute-force loop.
    const BruteForce reference(tris);
    Rng rng(8);
    size_t hits = 0;
    size_t checked = 0;
    for (int r = 0; r < 100; ++r) {
        // Short segments through a point on a random triangle's plane (inside
        // it or just past an edge), at t in [-0.5, 1.5]: some cross it, some stop short.
        const size_t t = 3 * rng.index(kCount);
        const glm::dvec3 v0(tris[t]);
        const double u = rng.uniform(-0.15, 1.0);
        const double v = rng.uniform(-0.15, 1.0 - std::max(u, 0.0));
        const glm::dvec3 through =
            v0 + u * (glm::dvec3(tris[t + 1]) - v0) + v * (glm::dvec3(tris[t + 2]) - v0);
        const glm::dvec3 direction = rng.point(glm::dvec3(-0.01), glm::dvec3(0.01));
        const Ray ray{through - direction * rng.uniform(-0.5, 1.5), direction, 1.0};
        const Reference want = reference.classify(ray);
        if (want == Reference::kAmbiguous) continue;
        ++checked;
        hits += want == Reference::kHit;
        EXPECT_EQ(bvh.occluded(ray.origin, ray.direction, ray.t_max), want == Reference::kHit);
    }
    EXPECT_GT(hits, 10u);
    EXPECT_GT(checked - hits, 10u);
}

}  // namespace
}  // namespace lc::client

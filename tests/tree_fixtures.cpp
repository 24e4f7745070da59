#include "tree_fixtures.h"

#include <gtest/gtest.h>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <utility>

#include "lightcuts/tree/gpu_layout.h"

namespace lc::test {
namespace {

struct TempNode {
    std::vector<int> lights;
    int left = -1, right = -1;
    int rep = 0;  // light index
};

float round_up(double v) {
    float f = float(v);
    return double(f) < v ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
}

float round_down(double v) {
    float f = float(v);
    return double(f) > v ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
}

}  // namespace

SceneLight make_light(LightType type, glm::vec3 position, float intensity, glm::vec3 color, float range) {
    SceneLight light;
    light.type = type;
    light.position = position;
    light.intensity = intensity;
    light.color = color;
    light.range = range;
    return light;
}

SurfacePoint surface(glm::dvec3 position, glm::dvec3 normal, glm::dvec3 albedo) {
    SurfacePoint p;
    p.position = position;
    p.normal = glm::normalize(normal);
    p.albedo = albedo;
    return p;
}

std::vector<SceneLight> random_lights_in_box(std::mt19937_64& rng, int count, LightType type, glm::vec3 lo,
                                             glm::vec3 hi, bool ranged) {
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<SceneLight> lights;
    for (int i = 0; i < count; ++i) {
        SceneLight l;
        l.guid = Guid{1, 2, 3, uint32_t(i + 1)};
        l.type = type;
        l.position = lo + (hi - lo) * glm::vec3(u(rng), u(rng), u(rng));
        glm::vec3 d(u(rng) - 0.5f, u(rng) - 0.5f, -u(rng) - 0.1f);
        l.direction = glm::normalize(d);
        l.color = glm::vec3(0.1f + u(rng), 0.1f + u(rng), 0.1f + u(rng));
        l.intensity = 0.1f + 5.0f * u(rng);
        l.range = ranged && type != LightType::kDirectional ? 1.0f + 6.0f * u(rng) : 0.0f;
        l.inner_cone_angle = 0.1f + 0.3f * u(rng);
        l.outer_cone_angle = l.inner_cone_angle + 0.05f + 0.9f * u(rng);
        lights.push_back(l);
    }
    return lights;
}

std::vector<SceneLight> mixed_scene(std::mt19937_64& rng) {
    std::vector<SceneLight> lights =
        random_lights_in_box(rng, 60, LightType::kPoint, {-6, -6, 0.5f}, {6, 6, 4}, true);
    auto spots = random_lights_in_box(rng, 30, LightType::kSpot, {-6, -6, 0.5f}, {6, 6, 4}, true);
    auto suns = random_lights_in_box(rng, 7, LightType::kDirectional, {0, 0, 0}, {0, 0, 0}, false);
    auto unbounded = random_lights_in_box(rng, 10, LightType::kPoint, {-6, -6, 0.5f}, {6, 6, 4}, false);
    for (auto* part : {&spots, &suns, &unbounded})
        lights.insert(lights.end(), part->begin(), part->end());
    return lights;
}

LightTree thesis_tree() {
    const glm::vec3 A(-300, 0, 150), B(-225, -45, 150), C(-300, 150, 150), D(0, 0, 150),
        E(150, 0, 150);
    auto node = [](glm::vec3 pos, float brightness, float radius, int left, int right, int rep) {
        LightTreeNode n;
        n.type = LightType::kPoint;
        n.position = pos;
        n.intensity = glm::vec3(brightness);
        n.brightness = brightness;
        n.radius = radius;
        n.range = 250.0f;
        n.left = left;
        n.right = right;
        n.representative = rep;
        return n;
    };
    LightTree tree;
    tree.nodes = {node(A, 27500, 700, 1, 2, 7),  node(A, 17500, 400, 3, 4, 7),
                  node(D, 10000, 400, 5, 6, 5),  node(A, 12500, 337.464f, 7, 8, 7),
                  node(C, 5000, 250, -1, -1, 4), node(D, 5000, 250, -1, -1, 5),
                  node(E, 5000, 250, -1, -1, 6), node(A, 5000, 250, -1, -1, 7),
                  node(B, 7500, 250, -1, -1, 8)};
    // Bounding boxes of each node's leaves.
    const std::vector<std::vector<glm::vec3>> leaves{
        {A, B, C, D, E}, {A, B, C}, {D, E}, {A, B}, {C}, {D}, {E}, {A}, {B}};
    for (size_t i = 0; i < leaves.size(); ++i) {
        tree.nodes[i].bbox_min = tree.nodes[i].bbox_max = leaves[i][0];
        for (const glm::vec3& p : leaves[i]) {
            tree.nodes[i].bbox_min = glm::min(tree.nodes[i].bbox_min, p);
            tree.nodes[i].bbox_max = glm::max(tree.nodes[i].bbox_max, p);
        }
    }
    tree.leaf_count = 5;
    return tree;
}

LightTree morton_pairing_tree(const std::vector<SceneLight>& lights, uint64_t seed) {
    LightTree tree;
    if (lights.empty()) return tree;
    std::mt19937_64 rng(seed);
    std::vector<TempNode> temp;
    std::vector<int> level;
    for (int i = 0; i < int(lights.size()); ++i) {
        temp.push_back({{i}, -1, -1, i});
        level.push_back(i);
    }
    glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
    auto key_point = [&](int i) {
        const SceneLight& l = lights[size_t(i)];
        return l.type == LightType::kDirectional ? l.direction : l.position;
    };
    for (int i : level) {
        lo = glm::min(lo, key_point(i));
        hi = glm::max(hi, key_point(i));
    }
    auto morton = [&](int i) {
        // One scale for every axis, so a thin axis does not get the high bits.
        const float extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-20f});
        const glm::vec3 t = (key_point(i) - lo) / extent;
        uint64_t code = 0;
        const uint32_t q[3] = {uint32_t(t.x * 1023.0f), uint32_t(t.y * 1023.0f),
                               uint32_t(t.z * 1023.0f)};
        for (int bit = 9; bit >= 0; --bit)
            for (int a = 0; a < 3; ++a) code = (code << 1) | ((q[a] >> bit) & 1u);
        // Types stay together, as the builders keep one tree per type.
        return (uint64_t(lights[size_t(i)].type) << 40) | code;
    };
    std::stable_sort(level.begin(), level.end(),
                     [&](int a, int b) { return morton(a) < morton(b); });
    while (level.size() > 1) {
        std::vector<int> next;
        for (size_t k = 0; k + 1 < level.size(); k += 2) {
            TempNode n;
            n.left = level[k];
            n.right = level[k + 1];
            n.lights = temp[size_t(n.left)].lights;
            n.lights.insert(n.lights.end(), temp[size_t(n.right)].lights.begin(),
                            temp[size_t(n.right)].lights.end());
            double bl = 0, br = 0;
            for (int i : temp[size_t(n.left)].lights) bl += lights[size_t(i)].intensity;
            for (int i : temp[size_t(n.right)].lights) br += lights[size_t(i)].intensity;
            const double u = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
            const bool pick_left = bl + br <= 0.0 ? true : u * (bl + br) < bl;
            n.rep = pick_left ? temp[size_t(n.left)].rep : temp[size_t(n.right)].rep;
            temp.push_back(n);
            next.push_back(int(temp.size() - 1));
        }
        if (level.size() % 2 == 1) next.push_back(level.back());
        level = next;
    }
    // Breadth-first renumbering from the root.
    std::vector<int> order;
    std::deque<int> queue{level.front()};
    while (!queue.empty()) {
        const int t = queue.front();
        queue.pop_front();
        order.push_back(t);
        if (temp[size_t(t)].left >= 0) {
            queue.push_back(temp[size_t(t)].left);
            queue.push_back(temp[size_t(t)].right);
        }
    }
    std::vector<int> new_index(temp.size(), -1);
    for (size_t i = 0; i < order.size(); ++i) new_index[size_t(order[i])] = int(i);
    std::vector<int> leaf_of_light(lights.size());
    for (size_t i = 0; i < order.size(); ++i) {
        if (temp[size_t(order[i])].left < 0)
            leaf_of_light[size_t(temp[size_t(order[i])].rep)] = int(i);
    }
    tree.nodes.resize(order.size());
    tree.leaf_count = uint32_t(lights.size());
    // Children before parents for the radius rule: walk the order backwards.
    for (size_t i = order.size(); i-- > 0;) {
        const TempNode& t = temp[size_t(order[i])];
        LightTreeNode& n = tree.nodes[i];
        const SceneLight& rep = lights[size_t(t.rep)];
        n.guid = rep.guid;
        n.type = rep.type;
        n.representative = leaf_of_light[size_t(t.rep)];
        n.position = rep.position;
        n.direction = rep.direction;
        n.range = rep.range;
        n.spot_cos_inner = float(std::cos(double(rep.inner_cone_angle)));
        n.spot_cos_outer = float(std::cos(double(rep.outer_cone_angle)));
        glm::dvec3 intensity(0.0);
        double brightness = 0.0;
        glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
        double min_cos = 1.0;
        bool mixed = false;
        for (int li : t.lights) {
            const SceneLight& l = lights[size_t(li)];
            intensity += glm::dvec3(l.color) * double(l.intensity);
            brightness += l.intensity;
            const glm::vec3 point = l.type == LightType::kDirectional ? l.direction : l.position;
            lo = glm::min(lo, point);
            hi = glm::max(hi, point);
            min_cos =
                std::min(min_cos, glm::dot(glm::dvec3(rep.direction), glm::dvec3(l.direction)));
            mixed = mixed || l.type != rep.type;
        }
        n.intensity = glm::vec3(intensity);
        n.brightness = float(brightness);
        n.bbox_min = lo;
        n.bbox_max = hi;
        n.cone_axis = rep.direction;
        n.cone_cos = std::clamp(round_down(min_cos - 1e-7), -1.0f, 1.0f);
        n.flags.set(kNodeMixedTypes, mixed);
        if (t.left < 0) {
            n.radius = rep.range > 0.0f ? rep.range : kUnboundedRadius;
        } else {
            n.left = new_index[size_t(t.left)];
            n.right = new_index[size_t(t.right)];
            double radius = 0.0;
            bool unbounded = false;
            for (int c : {n.left, n.right}) {
                const LightTreeNode& child = tree.nodes[size_t(c)];
                if (child.radius < 0.0f) unbounded = true;
                radius = std::max(radius,
                                  glm::length(glm::dvec3(child.position) - glm::dvec3(n.position)) +
                                      double(child.radius));
            }
            n.radius = unbounded ? kUnboundedRadius : round_up(radius);
        }
    }
    return tree;
}

LightTree make_pairing_tree(const std::vector<SceneLight>& lights) {
    struct Building {
        LightTreeNode node;
        int left = -1, right = -1;  // indices into `all`
    };
    std::vector<Building> all;
    auto leaf = [](const SceneLight& l) {
        LightTreeNode n;
        n.guid = l.guid;
        n.type = l.type;
        n.position = l.position;
        n.direction = l.direction;
        n.range = l.range;
        n.spot_cos_inner = std::cos(l.inner_cone_angle);
        n.spot_cos_outer = std::cos(l.outer_cone_angle);
        n.intensity = l.color * l.intensity;
        n.brightness = l.intensity;
        n.radius = l.range > 0.0f ? l.range : kUnboundedRadius;
        n.bbox_min = n.bbox_max = l.position;
        return n;
    };
    auto join = [&](int a, int b) {
        Building parent;
        const LightTreeNode& l = all[a].node;
        const LightTreeNode& r = all[b].node;
        parent.node = l;  // representative parameters: the left child's
        parent.node.intensity = l.intensity + r.intensity;
        parent.node.brightness = l.brightness + r.brightness;
        parent.node.flags.set(kNodeMixedTypes,
                              l.flags.mixed_types() || r.flags.mixed_types() || l.type != r.type);
        if (l.radius < 0.0f || r.radius < 0.0f) {
            parent.node.radius = kUnboundedRadius;
        } else {
            float reach = glm::length(r.position - l.position) + r.radius;
            parent.node.radius = std::max(l.radius, reach);
        }
        parent.node.bbox_min = glm::min(l.bbox_min, r.bbox_min);
        parent.node.bbox_max = glm::max(l.bbox_max, r.bbox_max);
        parent.left = a;
        parent.right = b;
        all.push_back(parent);
        return int(all.size()) - 1;
    };
    std::vector<int> level;
    for (const SceneLight& l : lights) {
        all.push_back({leaf(l)});
        level.push_back(int(all.size()) - 1);
    }
    while (level.size() > 1) {
        std::vector<int> next;
        for (size_t i = 0; i + 1 < level.size(); i += 2)
            next.push_back(join(level[i], level[i + 1]));
        if (level.size() % 2 == 1) next.push_back(level.back());
        level = next;
    }
    // Breadth-first renumbering from the root (iterative).
    LightTree tree;
    if (level.empty()) return tree;
    std::vector<int> order{level[0]};
    for (size_t i = 0; i < order.size(); ++i) {
        if (all[order[i]].left >= 0) {
            order.push_back(all[order[i]].left);
            order.push_back(all[order[i]].right);
        }
    }
    std::vector<int> new_index(all.size(), -1);
    for (size_t i = 0; i < order.size(); ++i) new_index[order[i]] = int(i);
    for (int old : order) {
        LightTreeNode n = all[old].node;
        n.left = all[old].left >= 0 ? new_index[all[old].left] : kNoChild;
        n.right = all[old].right >= 0 ? new_index[all[old].right] : kNoChild;
        tree.nodes.push_back(n);
    }
    // Representatives: follow left children down to a leaf (iteratively).
    for (size_t i = 0; i < tree.nodes.size(); ++i) {
        int32_t r = int32_t(i);
        while (tree.nodes[r].left != kNoChild) r = tree.nodes[r].left;
        tree.nodes[i].representative = r;
        if (tree.nodes[i].is_leaf()) ++tree.leaf_count;
    }
    return tree;
}

WalkTree walk_tree(const LightTree& tree) {
    Result<WalkTree> walk = make_walk_tree(tree);
    EXPECT_TRUE(walk.ok()) << walk.error();
    return walk.ok() ? std::move(walk).value() : WalkTree{};
}

bool finite3(const glm::dvec3& v) {
    return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

double max_channel(const glm::dvec3& v) {
    return std::max({v.x, v.y, v.z});
}

void expect_near_rel(const glm::dvec3& actual, const glm::dvec3& expected, double rel, double abs) {
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(actual[c], expected[c], rel * std::abs(expected[c]) + abs) << "channel " << c;
    }
}

void expect_within_cut_error(const CutResult& r, const glm::dvec3& exact, double ratio) {
    // Plus the rounding of summing the cut in another order.
    const double allowed =
        (ratio * r.cut_size * (1.0 + 1e-9) + 1e-12) * max_channel(r.radiance) + 1e-300;
    for (int c = 0; c < 3; ++c) {
        EXPECT_LE(std::abs(r.radiance[c] - exact[c]), allowed) << "channel " << c;
    }
}

}  // namespace lc::test

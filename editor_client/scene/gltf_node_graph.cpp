#include "editor_client/scene/gltf_node_graph.h"

#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <cstdint>
#include <span>
#include <string>

#include "editor_client/scene/gltf_finite.h"

namespace lc::client {
namespace {

// Each node's parent (-1: a root), every child checked to exist.
Result<std::vector<int>> parents_of(const GltfNodeTable& table, const GltfDiagnostics& diagnostics) {
    const int n = static_cast<int>(table.nodes.size());
    std::vector<int> parent(size_t(n), -1);
    for (int i = 0; i < n; ++i) {
        for (int child : table.children_of(table.nodes[size_t(i)])) {
            if (child < 0 || child >= n) {
                return diagnostics.fail("node " + std::to_string(i) + " lists child " +
                                        std::to_string(child) + ", which does not exist (the file has " +
                                        std::to_string(n) + " nodes)");
            }
            if (child == i) {
                return diagnostics.fail("recursive node graph: node " + std::to_string(i) +
                                        " is its own child");
            }
            if (parent[size_t(child)] != -1) {
                return diagnostics.fail("node " + std::to_string(child) + " has two parents (nodes " +
                                        std::to_string(parent[size_t(child)]) + " and " + std::to_string(i) +
                                        "); glTF node hierarchies must be trees");
            }
            parent[size_t(child)] = i;
        }
    }
    return parent;
}

// Walks up from every node once; a walk that meets itself is a cycle.
Status check_no_cycle(const std::vector<int>& parent, const GltfDiagnostics& diagnostics) {
    // 0: not yet seen, 1: on the current upward walk, 2: known to reach a root.
    std::vector<uint8_t> state(parent.size(), 0);
    std::vector<int> walk;
    for (size_t start = 0; start < parent.size(); ++start) {
        walk.clear();
        int j = static_cast<int>(start);
        while (j != -1 && state[size_t(j)] == 0) {
            state[size_t(j)] = 1;
            walk.push_back(j);
            j = parent[size_t(j)];
        }
        if (j != -1 && state[size_t(j)] == 1) {
            return diagnostics.fail("recursive node graph: node " + std::to_string(j) +
                                    " is its own ancestor");
        }
        for (int k : walk) state[size_t(k)] = 2;
    }
    return Ok{};
}

// No scene: every node nobody lists as a child.
std::vector<int> root_nodes(const GltfNodeTable& table) {
    std::vector<bool> is_child(table.nodes.size(), false);
    for (const GltfNode& node : table.nodes)
        for (int child : table.children_of(node)) is_child[size_t(child)] = true;
    std::vector<int> roots;
    for (size_t i = 0; i < table.nodes.size(); ++i)
        if (!is_child[i]) roots.push_back(static_cast<int>(i));
    return roots;
}

// A T/R/S property: absent, or `count` finite numbers.
Status check_property(std::span<const double> values, size_t count, const std::string& what,
                      const char* name) {
    if (values.empty()) return Ok{};
    if (values.size() != count) {
        return make_error(what + ": '" + name + "' needs " + std::to_string(count) + " numbers");
    }
    if (!all_finite(values)) return make_error(what + ": '" + name + "' has a non-finite value");
    return Ok{};
}

Result<glm::dmat4> matrix_transform(std::span<const double> matrix, const std::string& what) {
    if (matrix.size() != 16) {
        return make_error(what + ": 'matrix' has " + std::to_string(matrix.size()) + " numbers, expected 16");
    }
    if (!all_finite(matrix)) return make_error(what + ": 'matrix' has a non-finite value");
    return glm::make_mat4(matrix.data());  // both column-major
}

// translation * rotation * scale, each checked in that order.
Result<glm::dmat4> trs_transform(const GltfNodeTable& table, const GltfNode& node, const std::string& what) {
    const std::span<const double> translation = table.values(node.translation);
    const std::span<const double> rotation = table.values(node.rotation);
    const std::span<const double> scale = table.values(node.scale);
    glm::dmat4 m(1.0);
    if (Status valid = check_property(translation, 3, what, "translation"); !valid) return valid.failure();
    if (!translation.empty()) m[3] = glm::dvec4(translation[0], translation[1], translation[2], 1.0);
    if (Status valid = check_property(rotation, 4, what, "rotation"); !valid) return valid.failure();
    if (!rotation.empty()) {
        // glTF stores x, y, z, w; glm's constructor takes w first.
        const glm::dquat q(rotation[3], rotation[0], rotation[1], rotation[2]);
        const double len = glm::length(q);
        if (!(len > 1e-12)) return make_error(what + ": 'rotation' is a zero quaternion");
        m = m * glm::mat4_cast(q / len);
    }
    if (Status valid = check_property(scale, 3, what, "scale"); !valid) return valid.failure();
    if (!scale.empty()) {
        glm::dmat4 s(1.0);
        s[0][0] = scale[0];
        s[1][1] = scale[1];
        s[2][2] = scale[2];
        m = m * s;
    }
    return m;
}

}  // namespace

Status validate_gltf_node_graph(const GltfNodeTable& table, const GltfDiagnostics& diagnostics) {
    Result<std::vector<int>> parent = parents_of(table, diagnostics);
    if (!parent) return parent.failure();
    return check_no_cycle(*parent, diagnostics);
}

Result<std::vector<int>> gltf_scene_roots(const GltfNodeTable& table, int default_scene,
                                          GltfDiagnostics& diagnostics) {
    const int scene_count = static_cast<int>(table.scenes.size());
    const int node_count = static_cast<int>(table.nodes.size());
    if (default_scene >= scene_count) {
        return diagnostics.fail("'scene' is " + std::to_string(default_scene) + " but the file has " +
                                std::to_string(scene_count) + " scenes");
    }
    if (scene_count == 0) {
        if (node_count > 0) diagnostics.warn("the file has no scene; using every root node");
        return root_nodes(table);
    }
    const int chosen = default_scene >= 0 ? default_scene : 0;
    const std::span<const int32_t> listed = table.roots_of(size_t(chosen));
    for (int root : listed) {
        if (root < 0 || root >= node_count) {
            return diagnostics.fail("scene " + std::to_string(chosen) + " lists node " +
                                    std::to_string(root) + ", which does not exist (the file has " +
                                    std::to_string(node_count) + " nodes)");
        }
    }
    return std::vector<int>(listed.begin(), listed.end());
}

Result<glm::dmat4> gltf_local_transform(const GltfNodeTable& table, int node_index,
                                        const GltfDiagnostics& diagnostics) {
    const GltfNode& node = table.nodes[size_t(node_index)];
    const std::string what = "node " + std::to_string(node_index);
    const std::span<const double> matrix = table.values(node.matrix);
    Result<glm::dmat4> local =
        matrix.empty() ? trs_transform(table, node, what) : matrix_transform(matrix, what);
    if (!local) return diagnostics.fail(local.error());
    return local;
}

}  // namespace lc::client

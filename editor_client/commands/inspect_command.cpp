// editor_client inspect TREE.lcut [--json]: every node of a recorded result channel.
#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "editor_client/commands/command_errors.h"
#include "editor_client/commands/commands.h"
#include "protocol/channel_name.h"
#include "protocol/channel_records.h"
#include "protocol/dump.h"

namespace lc::client {
namespace {

nlohmann::json vec_json(const glm::vec3& v) { return nlohmann::json::array({v.x, v.y, v.z}); }

nlohmann::json node_json(const LightTreeNode& node, size_t index) {
    nlohmann::json j;
    j["index"] = index;
    j["guid"] = node.guid.to_hex();
    j["type"] = light_type_name(node.type);
    j["leaf"] = node.is_leaf();
    j["position"] = vec_json(node.position);
    j["direction"] = vec_json(node.direction);
    glm::vec3 color = node.brightness > 0.0f ? node.intensity / node.brightness : glm::vec3(0.0f);
    j["color"] = vec_json(color);
    j["brightness"] = node.brightness;
    j["intensity_rgb"] = vec_json(node.intensity);
    j["radius"] = node.radius;
    j["radius_unbounded"] = node.radius < 0.0f;
    j["falloff_exponent"] = node.falloff_exponent;
    j["left"] = node.left;
    j["right"] = node.right;
    j["representative"] = node.representative;
    j["bbox_min"] = vec_json(node.bbox_min);
    j["bbox_max"] = vec_json(node.bbox_max);
    j["cone_axis"] = vec_json(node.cone_axis);
    j["cone_cos"] = node.cone_cos;
    return j;
}

void print_text(const std::string& channel, const LightTree& tree) {
    std::printf("channel %s\n%zu nodes, %u leaves\n", channel.c_str(), tree.nodes.size(),
                tree.leaf_count);
    for (size_t i = 0; i < tree.nodes.size(); ++i) {
        const LightTreeNode& n = tree.nodes[i];
        std::printf(
            "[%zu] %s %s guid=%s pos=(%g, %g, %g) brightness=%g rgb=(%g, %g, %g) radius=%s "
            "falloff=%g children=(%d, %d) rep=%d\n",
            i, n.is_leaf() ? "leaf   " : "cluster", light_type_name(n.type), n.guid.to_hex().c_str(),
            n.position.x, n.position.y, n.position.z, n.brightness, n.intensity.x, n.intensity.y,
            n.intensity.z, n.radius < 0.0f ? "unbounded" : std::to_string(n.radius).c_str(),
            n.falloff_exponent, n.left, n.right, n.representative);
    }
}

}  // namespace

void register_inspect_command(CLI::App& app) {
    struct Options {
        std::string path;
        bool json = false;
    };
    auto options = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand("inspect", "Print every node of a light tree (.lcut dump)");
    cmd->add_option("tree", options->path, "Result channel dump written by 'bake -o'")->required();
    cmd->add_flag("--json", options->json, "Print JSON (shape in docs/PROTOCOL.md)");
    cmd->callback([options] {
        Result<ChannelDump> dump = read_dump(options->path);
        if (!dump) fail(options->path + ": " + dump.error());
        auto name = ChannelName::parse(dump->channel_name);
        if (!name || name->version != kLightcutsVersionGuid || name->extension != kLightcutsExtension)
            fail(options->path + ": channel '" + dump->channel_name +
                 "' is not a Lightcuts result channel (expected version " + kLightcutsVersionGuid.to_hex() +
                 ", extension ." + std::string(kLightcutsExtension) + ")");
        Result<LightTree> tree = decode_result_channel(dump->payload);
        if (!tree) fail(options->path + ": " + tree.error());
        if (options->json) {
            nlohmann::json j;
            j["channel"] = dump->channel_name;
            j["node_count"] = tree->nodes.size();
            j["leaf_count"] = tree->leaf_count;
            j["root"] = tree->nodes.empty() ? -1 : 0;
            nlohmann::json nodes = nlohmann::json::array();
            for (size_t i = 0; i < tree->nodes.size(); ++i) nodes.push_back(node_json(tree->nodes[i], i));
            j["nodes"] = std::move(nodes);
            std::cout << j.dump(2) << "\n";
        } else {
            print_text(dump->channel_name, *tree);
        }
    });
}

}  // namespace lc::client

// editor_client add-lights / remove-lights / make-scene: light layouts and
// procedural scenes written to glTF. Deterministic for a given seed.
#include <charconv>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "editor_client/commands/command_errors.h"
#include "editor_client/commands/commands.h"
#include "editor_client/commands/gltf_load_flags.h"
#include "editor_client/scene/gltf/gltf_loader.h"
#include "editor_client/scene/gltf/writer/gltf_writer.h"
#include "editor_client/scene/heavy_mesh.h"
#include "editor_client/scene/light_edit.h"
#include "editor_client/scene/scene_generator.h"

namespace lc::client {
namespace {

// "minx,miny,minz,maxx,maxy,maxz" -> a box.
Result<std::pair<glm::vec3, glm::vec3>> parse_box(const std::string& text) {
    float v[6];
    size_t start = 0;
    for (int i = 0; i < 6; ++i) {
        const size_t comma = text.find(',', start);
        const bool last = i == 5;
        if (last != (comma == std::string::npos)) {
            return make_error("--box '" + text + "' needs exactly 6 comma-separated numbers");
        }
        const std::string item = text.substr(start, last ? std::string::npos : comma - start);
        const char* begin = item.data();
        const char* end = begin + item.size();
        auto [ptr, ec] = std::from_chars(begin, end, v[i]);
        if (item.empty() || ec != std::errc() || ptr != end || !std::isfinite(v[i])) {
            return make_error("--box: '" + item + "' is not a finite number");
        }
        start = comma + 1;
    }
    return std::make_pair(glm::vec3(v[0], v[1], v[2]), glm::vec3(v[3], v[4], v[5]));
}

// Lights go inside the scene's bounds, 5% away from each side.
// "room | furnished-room | ... | heavy-room": from the generator's list, so a new scene is listed.
std::string every_scene_name() {
    std::string names;
    for (const std::string& name : named_scene_names()) names += name + " | ";
    return names + "heavy-room";
}

std::pair<glm::vec3, glm::vec3> default_box(const Scene& scene) {
    const glm::vec3 inset = (scene.bounds_max - scene.bounds_min) * 0.05f;
    return {scene.bounds_min + inset, scene.bounds_max - inset};
}

const char* type_choice_name(LightTypeChoice choice) {
    switch (choice) {
        case LightTypeChoice::kPoint:
            return "point";
        case LightTypeChoice::kSpot:
            return "spot";
        case LightTypeChoice::kDirectional:
            return "directional";
        case LightTypeChoice::kMixed:
            return "mixed";
    }
    return "unknown";
}

void register_add_lights_command(CLI::App& app) {
    struct Options {
        std::string scene;
        uint32_t count = 0;
        std::string layout;
        uint64_t seed = 0;
        std::string type = "point";
        std::string box;
        float intensity = 0.0f;
        float range = 0.0f;
        bool classic = false;
        std::string out;
        GltfLoadOptions gltf;
    };
    auto o = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand(
        "add-lights", "Add generated lights to a glTF scene (or to the empty room)");
    cmd->add_option("scene", o->scene, "glTF scene to add to; absent: the generated empty room");
    cmd->add_option("--count", o->count, "How many lights to add")->required();
    cmd->add_option("--layout", o->layout,
                    "random | grid | surface (surface: on the scene's triangles)")
        ->required();
    cmd->add_option("--seed", o->seed, "Seed of the random layout (default 0)");
    cmd->add_option("--type", o->type, "point | spot | directional | mixed (default point)");
    cmd->add_option("--box", o->box,
                    "minx,miny,minz,maxx,maxy,maxz (default: inside the room or the scene; "
                    "surface layout: triangles whose centroid is in it, default all)");
    CLI::Option* intensity =
        cmd->add_option("--intensity", o->intensity,
                        "Candela (point, spot) or lux (directional); default 10 cd and 1 lux");
    cmd->add_option("--range", o->range, "Range of point and spot lights; 0 = unbounded");
    cmd->add_flag("--classic", o->classic, "Mark the lights classic (shaded outside the tree)");
    add_gltf_load_flags(*cmd, o->gltf);
    cmd->add_option("-o,--output", o->out, "Output .gltf or .glb")->required();
    cmd->callback([o, intensity] {
        LightLayoutOptions layout;
        layout.count = o->count;
        layout.layout = or_fail(parse_light_layout(o->layout));
        layout.type = or_fail(parse_light_type_choice(o->type));
        layout.seed = o->seed;
        layout.range = o->range;
        layout.classic = o->classic;
        if (intensity->count() > 0) layout.intensity = o->intensity;

        Scene scene;
        std::pair<glm::vec3, glm::vec3> box;
        if (o->scene.empty()) {
            scene = make_room_scene();
            box = {kRoomLightBoxMin, kRoomLightBoxMax};
        } else {
            scene = or_fail(load_scene(o->scene, o->gltf));
            box = default_box(scene);
            if (o->box.empty() && scene.bounds_min == scene.bounds_max) {
                fail(o->scene +
                     " has no geometry or positioned lights to place lights in; give --box");
            }
        }
        // Surface lights: every triangle of the scene qualifies unless --box
        // says otherwise (a box inset from the walls would hold no wall's centroid).
        if (layout.layout == LightLayout::kSurface) box = {scene.bounds_min, scene.bounds_max};
        if (!o->box.empty()) box = or_fail(parse_box(o->box));
        layout.box_min = box.first;
        layout.box_max = box.second;
        layout.guid_salt = scene.guid;
        layout.surfaces = &scene;

        std::vector<SceneLight> lights = or_fail(generate_lights(layout));
        or_fail(add_lights(scene, lights));
        if (o->scene.empty()) {
            or_fail(write_scene_gltf(scene, o->out));
        } else {
            or_fail(write_lights_into_gltf(o->scene, scene.lights, o->out));
        }
        std::printf("added %u %s lights (%s layout, seed %llu) -> %s: %zu lights in total\n",
                    o->count, type_choice_name(layout.type), o->layout.c_str(),
                    static_cast<unsigned long long>(o->seed), o->out.c_str(), scene.lights.size());
    });
}

void register_remove_lights_command(CLI::App& app) {
    struct Options {
        std::string scene;
        std::string indices;
        std::string guids;
        bool all = false;
        std::string out;
        GltfLoadOptions gltf;
    };
    auto o = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand("remove-lights", "Remove lights from a glTF scene");
    cmd->add_option("scene", o->scene, "glTF scene")->required();
    CLI::Option* index = cmd->add_option("--index", o->indices, "Light indices: I[,J...]");
    CLI::Option* guid = cmd->add_option("--guid", o->guids, "Light GUIDs: G[,H...]");
    CLI::Option* all = cmd->add_flag("--all", o->all, "Remove every light");
    index->excludes(guid)->excludes(all);
    guid->excludes(all);
    add_gltf_load_flags(*cmd, o->gltf);
    cmd->add_option("-o,--output", o->out, "Output .gltf or .glb")->required();
    cmd->callback([o, index, guid, all] {
        if (index->count() + guid->count() + all->count() == 0) {
            fail("remove-lights needs one of --index, --guid or --all");
        }
        Scene scene = or_fail(load_scene(o->scene, o->gltf));
        const size_t before = scene.lights.size();
        if (o->all) {
            remove_all_lights(scene);
        } else if (index->count() > 0) {
            std::vector<size_t> indices = or_fail(parse_index_list(o->indices));
            or_fail(remove_lights_by_index(scene, indices));
        } else {
            std::vector<Guid> guids = or_fail(parse_guid_list(o->guids));
            or_fail(remove_lights_by_guid(scene, guids));
        }
        or_fail(write_lights_into_gltf(o->scene, scene.lights, o->out));
        std::printf("removed %zu of %zu lights -> %s: %zu lights left\n",
                    before - scene.lights.size(), before, o->out.c_str(), scene.lights.size());
    });
}

void register_make_scene_command(CLI::App& app) {
    struct Options {
        std::string name;
        std::string out;
        uint32_t triangles = 1000000;
    };
    auto o = std::make_shared<Options>();
    CLI::App* cmd = app.add_subcommand("make-scene", "Write a procedural scene to glTF");
    cmd->add_option("name", o->name, every_scene_name())->required();
    cmd->add_option("-o,--output", o->out, "Output .gltf or .glb")->required();
    cmd->add_option(
        "--triangles", o->triangles,
        "heavy-room: triangles of the tessellated sphere in the furnished room (default 1000000)");
    cmd->callback([o] {
        Scene scene = or_fail(o->name == "heavy-room" ? make_heavy_room_scene(o->triangles)
                                                      : make_named_scene(o->name));
        or_fail(write_scene_gltf(scene, o->out));
        // The GUID a bake will use is the written file's (directions pass
        // through quaternions and may differ in the last bit).
        Scene written = or_fail(load_scene(o->out));
        std::printf("%s -> %s: %zu meshes, %zu lights, %zu cameras, scene GUID %s\n",
                    o->name.c_str(), o->out.c_str(), written.meshes.size(), written.lights.size(),
                    written.cameras.size(), written.guid.to_hex().c_str());
    });
}

}  // namespace

void register_light_edit_commands(CLI::App& app) {
    register_add_lights_command(app);
    register_remove_lights_command(app);
    register_make_scene_command(app);
}

}  // namespace lc::client

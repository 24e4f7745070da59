#!/usr/bin/python3
"""Writes the small broken glTF files that tests/gltf_loader_test.cpp loads.

Each file breaks one rule on top of a valid one-triangle scene with one light,
so the loader's message can be checked case by case. Run on purpose only:
    /usr/bin/python3 tests/data/broken_gltf/make_broken_gltf.py
"""
import base64
import copy
import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def data_uri(raw):
    return "data:application/octet-stream;base64," + base64.b64encode(raw).decode()


def triangle_bytes(positions=((0, 0, 0), (1, 0, 0), (0, 1, 0)), indices=(0, 1, 2)):
    raw = b"".join(struct.pack("<3f", *p) for p in positions)
    idx = struct.pack("<%dH" % len(indices), *indices)
    idx += b"\0" * ((4 - len(idx) % 4) % 4)
    return raw, idx


def base_scene():
    pos, idx = triangle_bytes()
    raw = pos + idx
    return {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"mesh": 0}, {"translation": [0, 0, 2],
                                "extensions": {"KHR_lights_punctual": {"light": 0}}}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
             "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5123, "count": 3, "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pos)},
            {"buffer": 0, "byteOffset": len(pos), "byteLength": 6},
        ],
        "buffers": [{"byteLength": len(raw), "uri": data_uri(raw)}],
        "extensionsUsed": ["KHR_lights_punctual"],
        "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 5}]}},
    }


def write(name, doc):
    with open(os.path.join(HERE, name), "w") as f:
        json.dump(doc, f, indent=1, allow_nan=True)
        f.write("\n")


def case(name, edit):
    doc = copy.deepcopy(base_scene())
    edit(doc)
    write(name, doc)


def set_buffer(doc, raw, byte_length=None):
    doc["buffers"][0] = {"byteLength": len(raw) if byte_length is None else byte_length,
                         "uri": data_uri(raw)}


def main():
    write("valid_triangle.gltf", base_scene())

    with open(os.path.join(HERE, "bad_json.gltf"), "w") as f:
        f.write('{"asset": {"version": "2.0"}, "nodes": [{"mesh": 0}\n')
    open(os.path.join(HERE, "empty.gltf"), "w").close()
    with open(os.path.join(HERE, "truncated.glb"), "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 400) + struct.pack("<II", 200, 0x4E4F534A) + b"{")

    case("missing_buffer_file.gltf",
         lambda d: d["buffers"].__setitem__(0, {"byteLength": 44, "uri": "no_such_buffer.bin"}))
    # byteLength promises more than the data holds (embedded, then in a file).
    with open(os.path.join(HERE, "short.bin"), "wb") as f:
        f.write(b"\0" * 20)
    case("short_buffer_file.gltf",
         lambda d: d["buffers"].__setitem__(0, {"byteLength": 44, "uri": "short.bin"}))
    pos, idx = triangle_bytes()
    case("short_buffer.gltf", lambda d: set_buffer(d, pos + idx, byte_length=200))
    # The accessor claims 10 positions; its bufferView has 36 bytes.
    case("accessor_out_of_range.gltf", lambda d: d["accessors"][0].update(count=10))
    # The bufferView reaches past the end of its 44-byte buffer.
    case("buffer_view_out_of_range.gltf",
         lambda d: d["bufferViews"][0].update(byteOffset=40, byteLength=36))
    case("missing_buffer_view.gltf", lambda d: d["accessors"][0].update(bufferView=7))
    # Index 7 with 3 vertices.
    pos, idx = triangle_bytes(indices=(0, 1, 7))
    case("index_out_of_range.gltf", lambda d: set_buffer(d, pos + idx))
    # A NaN and an infinity in the positions.
    pos, idx = triangle_bytes(positions=((0, 0, 0), (float("nan"), 0, 0), (0, float("inf"), 0)))
    case("nonfinite_position.gltf", lambda d: set_buffer(d, pos + idx))
    case("vec2_positions.gltf", lambda d: d["accessors"][0].update(type="VEC2"))
    case("wrong_index_type.gltf", lambda d: d["accessors"][1].update(componentType=5126))
    case("missing_accessor.gltf",
         lambda d: d["meshes"][0]["primitives"][0]["attributes"].update(POSITION=9))

    # Node graphs: a cycle through two nodes, a node that is its own child,
    # a node with two parents, children and roots that do not exist.
    def cycle(d):
        d["nodes"][0]["children"] = [2]
        d["nodes"].append({"children": [0]})
    case("recursive_nodes.gltf", cycle)
    case("self_child_node.gltf", lambda d: d["nodes"][0].update(children=[0]))

    def two_parents(d):
        d["nodes"].append({"children": [0]})
        d["nodes"][1]["children"] = [0]
        d["scenes"][0]["nodes"] = [1, 2]
    case("two_parents.gltf", two_parents)
    case("missing_child.gltf", lambda d: d["nodes"][0].update(children=[42]))
    case("missing_scene_node.gltf", lambda d: d["scenes"][0].update(nodes=[0, 5]))
    case("bad_scene_index.gltf", lambda d: d.update(scene=3))
    case("missing_mesh.gltf", lambda d: d["nodes"][0].update(mesh=4))

    def no_scene(d):
        del d["scene"]
        del d["scenes"]
    case("no_scene.gltf", no_scene)

    # Transforms.
    case("matrix_wrong_length.gltf", lambda d: d["nodes"][1].update(matrix=[1, 0, 0, 0, 1]))
    case("zero_rotation.gltf", lambda d: d["nodes"][1].update(rotation=[0, 0, 0, 0]))
    case("huge_translation.gltf", lambda d: d["nodes"][1].update(translation=[1e39, 0, 0]))

    # Lights.
    lights = lambda d: d["extensions"]["KHR_lights_punctual"]["lights"]
    case("negative_intensity.gltf", lambda d: lights(d)[0].update(intensity=-2))
    case("unknown_light_type.gltf", lambda d: lights(d)[0].update(type="area"))
    case("bad_spot_angles.gltf", lambda d: lights(d).__setitem__(0, {
        "type": "spot", "spot": {"innerConeAngle": 0.8, "outerConeAngle": 0.5}}))
    case("spot_outer_too_wide.gltf", lambda d: lights(d).__setitem__(0, {
        "type": "spot", "spot": {"innerConeAngle": 0.1, "outerConeAngle": 2.0}}))
    case("negative_color.gltf", lambda d: lights(d)[0].update(color=[1, -0.5, 1]))
    case("negative_range.gltf", lambda d: lights(d)[0].update(range=-1))
    case("missing_light.gltf",
         lambda d: d["nodes"][1]["extensions"]["KHR_lights_punctual"].update(light=3))
    case("light_without_index.gltf",
         lambda d: d["nodes"][1]["extensions"].update(KHR_lights_punctual={}))
    case("directional_zero_scale.gltf", lambda d: (
        lights(d).__setitem__(0, {"type": "directional"}),
        d["nodes"][1].update(scale=[0, 0, 0])))

    # Not an error: points are skipped with a warning.
    case("points_primitive.gltf", lambda d: d["meshes"][0]["primitives"][0].update(mode=0))


if __name__ == "__main__":
    main()

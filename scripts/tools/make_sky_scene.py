"""Writes the demo's open-air scene: a 400 x 400 m ground (it reaches almost to
the horizon) and four boxes, no lights, as a glTF with an embedded buffer.
The file names its own sun and sky in the asset's extras (lightcuts_sky,
docs/ARCHITECTURE.md): bake, render and view take it without --sky."""
import base64
import json
import struct
import sys


def box(cx, cz, sx, sy, sz):
    """Six outward-facing quads (flat normals) of a box standing on y = 0."""
    faces = [((1, 0, 0), (0, 0, -1), (0, 1, 0)), ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
             ((0, 1, 0), (1, 0, 0), (0, 0, -1)), ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
             ((0, 0, 1), (1, 0, 0), (0, 1, 0)), ((0, 0, -1), (-1, 0, 0), (0, 1, 0))]
    half = (sx / 2, sy / 2, sz / 2)
    centre = (cx, sy / 2, cz)
    quads = []
    for n, u, v in faces:
        c = [centre[i] + n[i] * half[i] for i in range(3)]
        hu = [u[i] * half[i] for i in range(3)]
        hv = [v[i] * half[i] for i in range(3)]
        corners = [[c[i] - hu[i] - hv[i] for i in range(3)], [c[i] + hu[i] - hv[i] for i in range(3)],
                   [c[i] + hu[i] + hv[i] for i in range(3)], [c[i] - hu[i] + hv[i] for i in range(3)]]
        quads.append((corners, n))
    return quads


def main(path):
    ground = ([[-200, 0, 200], [200, 0, 200], [200, 0, -200], [-200, 0, -200]], (0, 1, 0))
    meshes = [([ground], 0), (box(-3, -2, 2, 3, 2), 1), (box(2.5, -3, 1.5, 5, 1.5), 2),
              (box(1, 1.5, 3, 1, 1), 1), (box(-1, 3, 0.8, 2, 0.8), 2)]
    blob = bytearray()
    views, accessors, gltf_meshes = [], [], []
    for quads, material in meshes:
        positions, normals, indices = [], [], []
        for corners, n in quads:
            base = len(positions)
            positions += corners
            normals += [n] * 4
            indices += [base, base + 1, base + 2, base, base + 2, base + 3]
        first = len(accessors)
        for data, fmt, kind, count in ((positions, "3f", "VEC3", len(positions)),
                                       (normals, "3f", "VEC3", len(normals)),
                                       (indices, "I", "SCALAR", len(indices))):
            offset = len(blob)
            for item in data:
                blob += struct.pack("<" + fmt, *(item if isinstance(item, (list, tuple)) else [item]))
            views.append({"buffer": 0, "byteOffset": offset, "byteLength": len(blob) - offset})
            accessor = {"bufferView": len(views) - 1, "componentType": 5126 if fmt == "3f" else 5125,
                        "count": count, "type": kind}
            if kind == "VEC3" and data is positions:
                accessor["min"] = [min(p[i] for p in positions) for i in range(3)]
                accessor["max"] = [max(p[i] for p in positions) for i in range(3)]
            accessors.append(accessor)
        gltf_meshes.append({"primitives": [{"attributes": {"POSITION": first, "NORMAL": first + 1},
                                            "indices": first + 2, "material": material}]})
    materials = [{"pbrMetallicRoughness": {"baseColorFactor": c + [1.0], "metallicFactor": 0.0,
                                           "roughnessFactor": 1.0}}
                 for c in ([0.45, 0.42, 0.38], [0.8, 0.35, 0.25], [0.3, 0.5, 0.75])]
    sky = {"elevation": 30.0, "azimuth": 40.0, "turbidity": 3.0, "intensity": 1.0}
    gltf = {"asset": {"version": "2.0", "extras": {"lightcuts_sky": sky}}, "scene": 0,
            "scenes": [{"nodes": list(range(len(gltf_meshes)))}],
            "nodes": [{"mesh": i} for i in range(len(gltf_meshes))],
            "meshes": gltf_meshes, "materials": materials, "accessors": accessors, "bufferViews": views,
            "buffers": [{"byteLength": len(blob),
                         "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}]}
    with open(path, "w") as f:
        json.dump(gltf, f)


if __name__ == "__main__":
    main(sys.argv[1])

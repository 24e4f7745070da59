"""Renders one of our glTF scenes in Blender's Cycles as an independent reference.

Run inside Blender (Debian's `blender`, 3.4):
    blender -b --factory-startup -P scripts/tools/cycles_reference.py -- SCENE.gltf -o OUT.pfm
        [--size 64x64] --camera ex,ey,ez,tx,ty,tz,fovy [--bounces B] [--samples N]
        [--lights all|punctual|emission] [--seed S]

The scene is lined up with the renderer (docs/ACCURACY.md, "Against an independent path
tracer"; SPEC section 13): every material becomes a Diffuse BSDF of the albedo the renderer's
shader integrates under diffuse light (lightcuts/device/material.glsl.h, bounce_albedo),
emission is one-sided (the front face only, as the renderer's), punctual lights have radius 0
and suns angle 0, the world is black, the pixel filter is a Gaussian 0.01 px wide (so every
sample lands on the pixel centre, as the renderer shades it), nothing is clamped or denoised.

Units: Blender's glTF importer turns I cd into I 4 pi / 683 W and E lux into E / 683 W/m^2, and
keeps emission (nits) as it is; the punctual lights' part is scaled by 683 so the PFM is in the
renderer's units. Each punctual light is rendered on its own at one sample per pixel (exact at the
pixel centre for direct light: no light-selection noise) and the images summed; emission and
bounces (`--bounces B` > 0) use `--samples`. `--bounces 0` is direct light only.

Limitations: base colour factors only (textures are left out), spot lights are refused (Cycles'
spot blend is not glTF's falloff), a roughness below 1 uses the model's lobe albedo fit.
"""
import argparse
import math
import os
import struct
import sys
import tempfile

import bpy
import numpy as np

# Blender 3.4's glTF importer still says np.bool, which Debian 12's numpy (1.24) no longer has.
if "bool" not in np.__dict__:
    np.bool = bool

# Blender's importer: W = cd x 4 pi / 683 and W/m^2 = lux / 683.
WATTS_PER_LUMEN = 683.0


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="cycles_reference.py", description=__doc__.split("\n")[0])
    p.add_argument("scene")
    p.add_argument("-o", "--output", required=True, help="linear colour PFM, the renderer's units")
    p.add_argument("--size", default="64x64")
    p.add_argument("--camera", required=True, help="ex,ey,ez,tx,ty,tz,fovy (glTF axes, degrees)")
    p.add_argument("--bounces", type=int, default=0, help="diffuse bounces; 0: direct light only")
    p.add_argument("--samples", type=int, default=1024, help="samples per pixel for emission and bounces")
    p.add_argument("--lights", choices=["all", "punctual", "emission"], default="all")
    p.add_argument("--seed", type=int, default=1)
    args = p.parse_args(argv)
    try:
        args.width, args.height = (int(v) for v in args.size.lower().split("x"))
        args.camera = [float(v) for v in args.camera.split(",")]
    except ValueError:
        p.error("--size WxH and --camera ex,ey,ez,tx,ty,tz,fovy take numbers")
    if len(args.camera) != 7:
        p.error("--camera takes 7 numbers: ex,ey,ez,tx,ty,tz,fovy")
    if args.bounces < 0 or args.samples < 1:
        p.error("--bounces must be >= 0 and --samples >= 1")
    return args


def lobe_hemispherical_albedo(exponent):
    """lightcuts/device/material.glsl.h's fit, for roughness below 1."""
    n = max(exponent, 0.0)
    beyond_mean = (1.0 + 0.01504 * n) / (1.0 + 0.5842 * n + 0.10863 * n * n)
    return (2.0 + beyond_mean) / 3.0


def bounce_albedo(base, metallic, roughness):
    """The albedo the renderer's shader integrates under diffuse light (bounce_albedo)."""
    m = min(max(metallic, 0.0), 1.0)
    r = min(max(roughness, 0.1), 1.0)
    exponent = max(4.0 / r ** 4 - 4.0, 0.0)
    glossy = lobe_hemispherical_albedo(exponent)
    return [min(max((1.0 - m) * 0.96 * b + (0.04 * (1.0 - m) + m * b) * glossy, 0.0), 1.0) for b in base]


def principled_inputs(material):
    """Base colour, metallic, roughness and emission the importer put on its Principled BSDF."""
    base, metallic, roughness, emission, strength = [1.0, 1.0, 1.0], 0.0, 1.0, [0.0, 0.0, 0.0], 1.0
    if material is None or not material.use_nodes:
        return base, metallic, roughness, emission, strength
    for node in material.node_tree.nodes:
        if node.type == "BSDF_PRINCIPLED":
            base = list(node.inputs["Base Color"].default_value)[:3]
            metallic = node.inputs["Metallic"].default_value
            roughness = node.inputs["Roughness"].default_value
            emission = list(node.inputs["Emission"].default_value)[:3]
            strength = node.inputs["Emission Strength"].default_value
        elif node.type == "EMISSION":
            emission = list(node.inputs["Color"].default_value)[:3]
            strength = node.inputs["Strength"].default_value
    return base, metallic, roughness, emission, strength


def replace_material(material, inputs, emission_on):
    """A Diffuse BSDF of the renderer's albedo; the front face adds the emission."""
    base, metallic, roughness, emission, strength = inputs
    albedo = bounce_albedo(base, metallic, roughness)
    nodes, links = material.node_tree.nodes, material.node_tree.links
    nodes.clear()
    out = nodes.new("ShaderNodeOutputMaterial")
    diffuse = nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Color"].default_value = (*albedo, 1.0)
    diffuse.inputs["Roughness"].default_value = 0.0
    radiance = [c * strength for c in emission]
    if not emission_on or max(radiance) <= 0.0:
        links.new(diffuse.outputs["BSDF"], out.inputs["Surface"])
        return
    emit = nodes.new("ShaderNodeEmission")
    emit.inputs["Color"].default_value = (*radiance, 1.0)
    emit.inputs["Strength"].default_value = 1.0
    front = nodes.new("ShaderNodeAddShader")
    links.new(diffuse.outputs["BSDF"], front.inputs[0])
    links.new(emit.outputs["Emission"], front.inputs[1])
    geometry = nodes.new("ShaderNodeNewGeometry")
    mix = nodes.new("ShaderNodeMixShader")
    links.new(geometry.outputs["Backfacing"], mix.inputs["Fac"])
    links.new(front.outputs["Shader"], mix.inputs[1])
    links.new(diffuse.outputs["BSDF"], mix.inputs[2])
    links.new(mix.outputs["Shader"], out.inputs["Surface"])


def gltf_to_blender(v):
    """glTF's +Y up to Blender's +Z up (the importer's conversion)."""
    return (v[0], -v[2], v[1])


def place_camera(scene, camera, width, height):
    from mathutils import Matrix, Vector
    eye, target = Vector(gltf_to_blender(camera[0:3])), Vector(gltf_to_blender(camera[3:6]))
    forward = (target - eye).normalized()
    right = forward.cross(Vector((0.0, 0.0, 1.0)))
    if right.length < 1e-9:
        right = Vector((1.0, 0.0, 0.0))
    right.normalize()
    up = right.cross(forward)
    data = bpy.data.cameras.new("reference")
    data.sensor_fit = "VERTICAL"
    data.angle_y = math.radians(camera[6])
    data.clip_start = 1e-4
    data.clip_end = 1e6
    obj = bpy.data.objects.new("reference", data)
    scene.collection.objects.link(obj)
    rotation = Matrix((right, up, -forward)).transposed()
    obj.matrix_world = Matrix.Translation(eye) @ rotation.to_4x4()
    scene.camera = obj
    scene.render.resolution_x, scene.render.resolution_y = width, height
    scene.render.resolution_percentage = 100
    scene.render.pixel_aspect_x = scene.render.pixel_aspect_y = 1.0


def set_up_cycles(scene, args):
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.pixel_filter_type = "GAUSSIAN"
    c.filter_width = 0.01
    c.use_denoising = False
    c.use_adaptive_sampling = False
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.light_sampling_threshold = 0.0
    c.max_bounces = c.diffuse_bounces = args.bounces
    c.glossy_bounces = c.transmission_bounces = c.volume_bounces = 0
    c.caustics_reflective = c.caustics_refractive = False
    c.seed = args.seed
    scene.render.film_transparent = False
    scene.view_settings.view_transform = "Standard"
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    world.node_tree.nodes["Background"].inputs["Strength"].default_value = 0.0
    scene.world = world
    scene.render.image_settings.file_format = "OPEN_EXR"
    scene.render.image_settings.color_depth = "32"
    scene.render.image_settings.exr_codec = "ZIP"


def render_pixels(scene, samples, folder, name):
    """Renders the scene and returns its linear RGB, rows bottom to top (as PFM stores them)."""
    scene.cycles.samples = samples
    path = os.path.join(folder, name + ".exr")
    scene.render.filepath = path
    bpy.ops.render.render(write_still=True)
    image = bpy.data.images.load(path)
    pixels = np.array(image.pixels[:], dtype=np.float64).reshape(image.size[1], image.size[0], 4)[:, :, :3]
    bpy.data.images.remove(image)
    return pixels


def write_pfm(path, pixels):
    height, width = pixels.shape[:2]
    with open(path, "wb") as f:
        f.write(b"PF\n%d %d\n-1.0\n" % (width, height))
        f.write(pixels.astype("<f4").tobytes())


def main():
    args = parse_args()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.ops.import_scene.gltf(filepath=os.path.abspath(args.scene))
    scene = bpy.context.scene
    lights = [o for o in scene.objects if o.type == "LIGHT"]
    for light in lights:
        if light.data.type == "SPOT":
            sys.exit("cycles_reference: spot light '%s': Cycles' spot blend is not glTF's falloff; "
                     "compare spots as point lights times the falloff" % light.name)
        if light.data.type not in ("POINT", "SUN"):
            sys.exit("cycles_reference: light '%s' of type %s is not a glTF light" % (light.name, light.data.type))
        light.data.shadow_soft_size = 0.0
        if light.data.type == "SUN":
            light.data.angle = 0.0
    for obj in [o for o in scene.objects if o.type == "CAMERA"]:
        obj.hide_render = True
    # Read once: replacing a material's nodes drops the importer's.
    inputs = {m.name: principled_inputs(m) for m in bpy.data.materials if m.use_nodes}
    for material in bpy.data.materials:
        if material.name in inputs:
            replace_material(material, inputs[material.name], emission_on=False)
    place_camera(scene, args.camera, args.width, args.height)
    set_up_cycles(scene, args)
    total = np.zeros((args.height, args.width, 3))
    with tempfile.TemporaryDirectory() as folder:
        if args.lights in ("all", "punctual"):
            for light in lights:
                for other in lights:
                    other.hide_render = other is not light
                # One sample: the light's exact direct value at the pixel centre (bounces add noise).
                samples = 1 if args.bounces == 0 else args.samples
                total += WATTS_PER_LUMEN * render_pixels(scene, samples, folder, "light")
        if args.lights in ("all", "emission"):
            emitting = any(max(i[3]) * i[4] > 0.0 for i in inputs.values())
            if emitting:
                for light in lights:
                    light.hide_render = True
                for material in bpy.data.materials:
                    if material.name in inputs:
                        replace_material(material, inputs[material.name], emission_on=True)
                total += render_pixels(scene, args.samples, folder, "emission")
    write_pfm(args.output, total)
    print("cycles_reference: %s -> %s (%dx%d, %d punctual lights, %d bounces)" %
          (args.scene, args.output, args.width, args.height, len(lights), args.bounces))


if __name__ == "__main__":
    main()

"""Renders a glTF room with Blender Cycles (CPU) as an equirectangular panorama.

Run inside Blender, arguments after `--`:

    blender -b --factory-startup -noaudio -t 2 --python render_cycles.py -- \
        --gltf room_0.gltf --out cycles.exr --width 256 --height 128 --samples 64 --seed 1 \
        --camera=0.463,1.694,-0.481 [--bounces 7] [--rotation 90,0,0] [--json cycles.json]

The output matches `phyir render` as closely as Cycles allows (see docs/cycles-comparison.md):
- panorama: equirectangular over the full sphere, world-aligned like ours (conventions.md);
  `--camera` is in glTF coordinates (+Y up), converted here to Blender's Z-up;
- film: linear EXR, float RGB, box pixel filter of width 1 (ours), no denoising, no
  adaptive sampling, view transform Standard with exposure 0 and no look;
- unbiased light transport: no clamping, no glossy blur, caustics on, no light threshold,
  no path guiding, MIS between light sampling and BSDF sampling (ours);
- black world (our renders have no environment unless asked);
- glTF alpha (BLEND) as the importer maps it, a Transparent BSDF mixed in by the Principled
  Alpha input (kept by --materials ue4 too), with no limit on the blended surfaces a path
  crosses (transparent_max_bounces 1024: phyir does not count them as bounces);
- punctual lights (KHR_lights_punctual) as delta lights: the importer's 0.25 m lamp radius
  and the sun's 0.526 degree angle are set to 0; the lights are listed in the JSON.

`--bounces` is Cycles' count, which counts the bounces after the first hit: Cycles'
`max_bounces = B` renders the paths of `phyir render --max-bounces B+1`
(measured in docs/cycles-comparison.md).

The JSON written next to the image records the settings and the times: `render_seconds`
is Cycles' own render time (synchronisation, BVH build and kernel loading excluded),
`render_call_seconds` the wall time of the render operator, `import_seconds` the glTF import.
"""
import argparse
import ctypes
import json
import math
import os
import re
import resource
import sys
import tempfile
import time

import bpy
import mathutils
import numpy

# Blender 3.4's glTF importer uses np.bool, which numpy 1.24 removed.
numpy.bool = bool


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="render_cycles.py")
    p.add_argument("--gltf", required=True)
    p.add_argument("--out", required=True, help="output EXR path")
    p.add_argument("--json", help="settings and timings (default: OUT with .json)")
    p.add_argument("--width", type=int, default=256)
    p.add_argument("--height", type=int, default=128)
    p.add_argument("--samples", type=int, default=16)
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--bounces", type=int, default=7, help="Cycles max bounces (ours minus one)")
    p.add_argument("--camera", required=True, help="x,y,z in glTF coordinates (+Y up); write --camera=X,Y,Z when X is negative")
    p.add_argument("--rotation", default="90,0,0", help="camera Euler XYZ, degrees (Blender frame)")
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--pattern", default="PROGRESSIVE_MULTI_JITTER",
                   help="Cycles sampling pattern: PROGRESSIVE_MULTI_JITTER (default) or SOBOL")
    p.add_argument("--materials", choices=["principled", "ue4"], default="principled",
                   help="principled: the importer's Principled BSDF as is; ue4: rebuilt as Lambert "
                        "diffuse + GGX specular, the terms of our BRDF (see below)")
    p.add_argument("--depth-pass", action="store_true",
                   help="also write OUT_depth.exr, Cycles' Z pass (distance for panoramas)")
    return p.parse_args(argv)


def gltf_to_blender(x, y, z):
    """glTF +Y up to Blender +Z up, as the importer converts: (x, y, z) -> (x, -z, y)."""
    return (x, -z, y)


def import_scene(path):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    start = time.perf_counter()
    bpy.ops.import_scene.gltf(filepath=path)
    return time.perf_counter() - start


def make_lights_delta():
    """Turns every imported lamp into a delta light, as glTF's KHR_lights_punctual defines them.

    Blender's glTF importer gives each lamp Blender's default radius (shadow_soft_size 0.25 m)
    and each sun its default angle (0.526 degrees): set to 0, so that Cycles renders a point,
    a spot and a directional light. Returns what was found, for the report: Blender's units
    (point and spot: W, sun: W/m^2) and, per the importer (convert_lighting_mode SPEC),
    point/spot W = cd * 4 pi / 683, sun W/m^2 = lx / 683.
    """
    lights = []
    for obj in bpy.data.objects:
        if obj.type != "LIGHT":
            continue
        light = obj.data
        entry = {"object": obj.name, "type": light.type, "energy": light.energy,
                 "color": list(light.color)}
        if light.type == "SUN":
            entry["angle_imported"] = light.angle
            light.angle = 0.0
        else:
            entry["radius_imported"] = light.shadow_soft_size
            light.shadow_soft_size = 0.0
        if light.type == "SPOT":
            entry["spot_size"] = light.spot_size
            entry["spot_blend"] = light.spot_blend
        world = obj.matrix_world
        position = world.translation
        direction = (world.to_3x3() @ mathutils.Vector((0.0, 0.0, -1.0))).normalized()
        entry["position_gltf"] = [position.x, position.z, -position.y]
        entry["direction_gltf"] = [direction.x, direction.z, -direction.y]
        lights.append(entry)
    return lights


def input_source(socket):
    """What feeds an input socket: (linked output socket, None) or (None, default value)."""
    if socket.is_linked:
        return socket.links[0].from_socket, None
    value = socket.default_value
    return None, (tuple(value) if hasattr(value, "__len__") else value)


def connect(tree, source, target):
    socket, value = source
    if socket is not None:
        tree.links.new(socket, target)
    else:
        target.default_value = value


def rebuild_as_ue4(material):
    """Replaces the Principled BSDF by the terms of our BRDF (docs/brdf.md), where Cycles has them.

    Principled v1 differs from the UE4 BRDF in its diffuse lobe (Burley's, with a
    roughness-dependent retro-reflection, instead of Lambert). Rebuilt here as
      Diffuse BSDF (roughness 0, i.e. Lambert) with colour base * (1 - metallic)
    + Principled with metallic 1 and base colour mix(0.04, base, metallic), i.e. only its GGX
      specular lobe with F0 = 0.04 for dielectrics and the base colour for metals,
    + the emission, unchanged.
    What stays different: Cycles' exact Smith G instead of Schlick's k = (R + 1)^2 / 8 and its
    Fresnel interpolation instead of Schlick's.
    Glass (KHR_materials_transmission, Principled "Transmission" > 0) becomes what phyir renders
    (docs/conventions.md, material model): the terms above mixed with a smooth Glass BSDF
    (distribution SHARP, the material's IOR, colour = base colour) by the transmission factor;
    phyir ignores the roughness for the refractive lobe, so the glass is sharp here too. Left
    different: Cycles' Glass colour tints its reflection as well, phyir's tint only the refraction.
    """
    tree = material.node_tree
    principled = next((n for n in tree.nodes if n.bl_idname == "ShaderNodeBsdfPrincipled"), None)
    if principled is None:
        return False
    transmission = input_source(principled.inputs["Transmission"])
    output = next(n for n in tree.nodes if n.bl_idname == "ShaderNodeOutputMaterial")
    base = input_source(principled.inputs["Base Color"])
    metallic = input_source(principled.inputs["Metallic"])
    roughness = input_source(principled.inputs["Roughness"])
    normal = input_source(principled.inputs["Normal"])

    diffuse_colour = tree.nodes.new("ShaderNodeMixRGB")  # base * (1 - metallic)
    diffuse_colour.blend_type = "MIX"
    connect(tree, metallic, diffuse_colour.inputs["Fac"])
    connect(tree, base, diffuse_colour.inputs["Color1"])
    diffuse_colour.inputs["Color2"].default_value = (0.0, 0.0, 0.0, 1.0)
    diffuse = tree.nodes.new("ShaderNodeBsdfDiffuse")
    diffuse.inputs["Roughness"].default_value = 0.0
    tree.links.new(diffuse_colour.outputs["Color"], diffuse.inputs["Color"])

    f0 = tree.nodes.new("ShaderNodeMixRGB")  # mix(0.04, base, metallic)
    f0.blend_type = "MIX"
    connect(tree, metallic, f0.inputs["Fac"])
    f0.inputs["Color1"].default_value = (0.04, 0.04, 0.04, 1.0)
    connect(tree, base, f0.inputs["Color2"])
    specular = tree.nodes.new("ShaderNodeBsdfPrincipled")
    specular.distribution = "GGX"
    specular.inputs["Metallic"].default_value = 1.0
    tree.links.new(f0.outputs["Color"], specular.inputs["Base Color"])
    connect(tree, roughness, specular.inputs["Roughness"])
    connect(tree, input_source(principled.inputs["Emission"]), specular.inputs["Emission"])
    connect(tree, input_source(principled.inputs["Emission Strength"]), specular.inputs["Emission Strength"])
    if normal[0] is not None:
        tree.links.new(normal[0], diffuse.inputs["Normal"])
        tree.links.new(normal[0], specular.inputs["Normal"])

    add = tree.nodes.new("ShaderNodeAddShader")
    tree.links.new(diffuse.outputs["BSDF"], add.inputs[0])
    tree.links.new(specular.outputs["BSDF"], add.inputs[1])
    surface = add.outputs["Shader"]
    if transmission[0] is not None or transmission[1] > 0.0:
        glass = tree.nodes.new("ShaderNodeBsdfGlass")
        glass.distribution = "SHARP"
        connect(tree, base, glass.inputs["Color"])
        connect(tree, input_source(principled.inputs["IOR"]), glass.inputs["IOR"])
        if normal[0] is not None:
            tree.links.new(normal[0], glass.inputs["Normal"])
        mix = tree.nodes.new("ShaderNodeMixShader")  # (1 - t) BRDF + t glass
        connect(tree, transmission, mix.inputs["Fac"])
        tree.links.new(surface, mix.inputs[1])
        tree.links.new(glass.outputs["BSDF"], mix.inputs[2])
        surface = mix.outputs["Shader"]
    alpha = input_source(principled.inputs["Alpha"])
    if alpha[0] is not None or alpha[1] < 1.0:  # glTF alpha (BLEND): as Principled's Alpha, mix(Transparent, BRDF + emission, alpha)
        transparent = tree.nodes.new("ShaderNodeBsdfTransparent")
        mix_alpha = tree.nodes.new("ShaderNodeMixShader")
        connect(tree, alpha, mix_alpha.inputs["Fac"])
        tree.links.new(transparent.outputs["BSDF"], mix_alpha.inputs[1])
        tree.links.new(surface, mix_alpha.inputs[2])
        surface = mix_alpha.outputs["Shader"]
    tree.links.new(surface, output.inputs["Surface"])
    return True


def setup_world(scene):
    world = bpy.data.worlds.new("black")
    world.use_nodes = True
    background = world.node_tree.nodes["Background"]
    background.inputs["Color"].default_value = (0.0, 0.0, 0.0, 1.0)
    background.inputs["Strength"].default_value = 0.0
    scene.world = world


def setup_camera(scene, position, rotation_degrees):
    data = bpy.data.cameras.new("panorama")
    data.type = "PANO"
    data.cycles.panorama_type = "EQUIRECTANGULAR"
    data.cycles.latitude_min, data.cycles.latitude_max = -math.pi / 2, math.pi / 2
    data.cycles.longitude_min, data.cycles.longitude_max = -math.pi, math.pi
    data.clip_start = 1e-4
    data.clip_end = 1e4
    camera = bpy.data.objects.new("panorama", data)
    scene.collection.objects.link(camera)
    camera.location = gltf_to_blender(*position)
    camera.rotation_mode = "XYZ"
    camera.rotation_euler = [math.radians(a) for a in rotation_degrees]
    scene.camera = camera


def setup_cycles(scene, args):
    scene.render.engine = "CYCLES"
    c = scene.cycles
    c.device = "CPU"
    c.feature_set = "SUPPORTED"
    c.samples = args.samples
    c.seed = args.seed
    c.use_animated_seed = False
    c.sampling_pattern = args.pattern
    c.use_adaptive_sampling = False
    c.use_denoising = False
    c.time_limit = 0.0
    # Unbiased transport: nothing clamped, blurred, culled or guided.
    c.max_bounces = args.bounces
    c.diffuse_bounces = args.bounces
    c.glossy_bounces = args.bounces
    c.transmission_bounces = args.bounces
    c.volume_bounces = 0
    c.transparent_max_bounces = 1024  # blended (alpha) surfaces crossed: not bounces in phyir, no limit there
    c.min_light_bounces = 0
    c.min_transparent_bounces = 0
    c.sample_clamp_direct = 0.0
    c.sample_clamp_indirect = 0.0
    c.blur_glossy = 0.0
    c.caustics_reflective = True
    c.caustics_refractive = True
    c.light_sampling_threshold = 0.0
    c.direct_light_sampling_type = "MULTIPLE_IMPORTANCE_SAMPLING"
    c.use_guiding = False
    c.use_fast_gi = False
    c.use_camera_cull = False
    c.use_distance_cull = False
    # Film: box filter over the pixel, like ours.
    c.pixel_filter_type = "BOX"
    c.filter_width = 1.0
    c.film_exposure = 1.0
    scene.render.film_transparent = False
    scene.render.use_persistent_data = False
    scene.render.threads_mode = "FIXED"
    scene.render.threads = args.threads
    scene.render.resolution_x = args.width
    scene.render.resolution_y = args.height
    scene.render.resolution_percentage = 100
    scene.render.use_compositing = False
    scene.render.use_sequencer = False
    view_layer = scene.view_layers[0]
    view_layer.cycles.denoising_store_passes = False
    view_layer.use_pass_z = args.depth_pass
    # Scene-linear output: Standard view, exposure 0, gamma 1, no look.
    scene.display_settings.display_device = "sRGB"
    scene.view_settings.view_transform = "Standard"
    scene.view_settings.look = "None"
    scene.view_settings.exposure = 0.0
    scene.view_settings.gamma = 1.0
    scene.view_settings.use_curve_mapping = False
    settings = scene.render.image_settings
    settings.file_format = "OPEN_EXR_MULTILAYER" if args.depth_pass else "OPEN_EXR"
    settings.color_mode = "RGB"
    settings.color_depth = "32"
    settings.exr_codec = "ZIP"


def render_capturing_stdout():
    """Renders and writes the still; returns Blender's status lines, wall and CPU seconds.

    Cycles reports its progress on the C stdout, so file descriptor 1 is redirected to a
    temporary file for the duration of the render and the lines are echoed afterwards.
    """
    libc = ctypes.CDLL(None)
    sys.stdout.flush()
    libc.fflush(None)
    saved = os.dup(1)
    with tempfile.TemporaryFile(mode="w+b") as capture:
        os.dup2(capture.fileno(), 1)
        try:
            cpu_start = resource.getrusage(resource.RUSAGE_SELF)
            start = time.perf_counter()
            bpy.ops.render.render(write_still=True)
            wall = time.perf_counter() - start
            cpu_end = resource.getrusage(resource.RUSAGE_SELF)
        finally:
            libc.fflush(None)
            os.dup2(saved, 1)
            os.close(saved)
        capture.seek(0)
        log = capture.read().decode("utf-8", "replace")
    sys.stdout.write(log)
    cpu = (cpu_end.ru_utime - cpu_start.ru_utime) + (cpu_end.ru_stime - cpu_start.ru_stime)
    return log, wall, cpu


def cycles_render_seconds(log):
    """Cycles' path-tracing time: its clock at "Finished" minus its clock at "Sample 0/N".

    Everything before "Sample 0/N" is set-up (kernel loading, shaders, BVH build, lights).
    Status lines read "Fra:1 Mem:... | Time:00:09.18 | ... | Sample 16/16".
    """
    def clock(line):
        m = re.search(r"\| Time:(?:(\d+):)?(\d+):(\d+(?:\.\d+)?)", line)
        if not m:
            return None
        h, mnt, s = m.groups()
        return (int(h) if h else 0) * 3600 + int(mnt) * 60 + float(s)

    start = end = None
    for line in log.splitlines():
        if re.search(r"\| Sample 0/\d+\s*$", line) and start is None:
            start = clock(line)
        elif re.search(r"\| Finished\s*$", line):
            end = clock(line)
    if start is None or end is None:
        return None
    return end - start


def main():
    args = parse_args()
    position = [float(v) for v in args.camera.split(",")]
    rotation = [float(v) for v in args.rotation.split(",")]
    if len(position) != 3 or len(rotation) != 3:
        sys.exit(f"render_cycles.py: --camera and --rotation take 3 numbers, got '{args.camera}', '{args.rotation}'")

    import_seconds = import_scene(args.gltf)
    scene = bpy.context.scene
    lights = make_lights_delta()
    for light in lights:
        extra = "".join(f" {k} {light[k]:.4f}" for k in ("spot_size", "spot_blend") if k in light)
        unit = "W/m^2" if light["type"] == "SUN" else "W"
        print(f"render_cycles.py: light '{light['object']}' {light['type']} {light['energy']:.4f} {unit}{extra}"
              f" at {[round(v, 4) for v in light['position_gltf']]} (glTF) made delta")
    setup_world(scene)
    setup_camera(scene, position, rotation)
    setup_cycles(scene, args)
    rebuilt = []
    if args.materials == "ue4":
        rebuilt = [m.name for m in bpy.data.materials if m.node_tree and rebuild_as_ue4(m)]

    scene.render.filepath = args.out
    log, render_call_seconds, cpu_seconds = render_capturing_stdout()
    render_seconds = cycles_render_seconds(log)

    emissive = []
    for mat in bpy.data.materials:
        if mat.node_tree and "Principled BSDF" in mat.node_tree.nodes:
            node = mat.node_tree.nodes["Principled BSDF"]
            strength = node.inputs["Emission Strength"].default_value
            colour = list(node.inputs["Emission"].default_value)[:3]
            if strength > 0 and max(colour) > 0:
                emissive.append({"material": mat.name, "emission": colour, "strength": strength,
                                 "backface_culling": mat.use_backface_culling})
    c = scene.cycles
    report = {
        "blender": bpy.app.version_string,
        "gltf": args.gltf,
        "out": args.out,
        "width": args.width,
        "height": args.height,
        "samples": args.samples,
        "seed": args.seed,
        "threads": scene.render.threads,
        "camera_gltf": position,
        "camera_blender": list(scene.camera.location),
        "rotation_degrees": rotation,
        "materials": args.materials,
        "materials_rebuilt_as_ue4": rebuilt,
        "settings": {k: getattr(c, k) for k in [
            "device", "sampling_pattern", "max_bounces", "diffuse_bounces", "glossy_bounces",
            "transmission_bounces", "min_light_bounces", "sample_clamp_direct", "sample_clamp_indirect",
            "blur_glossy", "caustics_reflective", "caustics_refractive", "light_sampling_threshold",
            "direct_light_sampling_type", "use_guiding", "use_adaptive_sampling", "use_denoising",
            "pixel_filter_type", "filter_width"]},
        "view_transform": scene.view_settings.view_transform,
        "emissive_materials": emissive,
        "lights": lights,
        "timings": {"import_seconds": import_seconds, "render_call_seconds": render_call_seconds,
                    "render_seconds": render_seconds, "render_call_cpu_seconds": cpu_seconds},
    }
    out_json = args.json or re.sub(r"\.exr$", "", args.out) + ".json"
    with open(out_json, "w") as f:
        json.dump(report, f, indent=2)
    print(f"render_cycles.py: {args.samples} spp in {render_call_seconds:.3f} s "
          f"(Cycles render time {render_seconds}), wrote {args.out}")


main()

"""Builds a small closed room lit only through blended (alphaMode BLEND) lamp glass and exports it as glTF.

The test asset for glTF `alphaMode: BLEND` in light transport, compared with Cycles by
scripts/cycles/compare_glass_lamp.sh: modelled in Blender, written by Blender's own glTF
exporter (io_scene_gltf2), lights as KHR_lights_punctual. Run with a factory startup:

    blender -b --factory-startup --python-exit-code 1 \
        --python scripts/blender/make_glass_lamp_room.py -- \
        [--out tests/data/gltf/blender_glass_lamp/glass_lamp_room.gltf]

What it builds (Blender coordinates, +Z up, metres; glTF (x, y, z) = Blender (x, z, -y)):
- a closed room, inside 4 x 3 x 2.6 m (x in [-2, 2], y in [-1.5, 1.5], z in [0, 2.6]), floor,
  ceiling and walls as boxes 0.1 m thick, no openings: every bit of light comes from the lamps;
  off-white walls and ceiling, a blue-grey floor, a wooden table, a low cabinet;
- a table lamp on the table: a dark base and stem under a glass globe (UV sphere, radius
  0.12 m, smooth shaded; base colour near white, roughness 0.35, alpha 0.35), a 40 W point
  light of radius 0 at the globe's centre;
- a ceiling pendant: a cord, a socket, an open lampshade (a truncated cone open at both ends,
  radius 0.22 m 0.12 m below the light and 0.11 m 0.12 m above it; ochre fabric, roughness
  0.9, alpha 0.6), a 60 W point light of radius 0 inside it, 5 cm below the socket: the
  ceiling gets the light through the fabric and, in a ring, through the top opening, the
  floor through the bottom opening;
- a wall sconce on the north wall (y = 1.5): an emissive bulb (sphere, radius 0.05 m,
  emission (1, 0.85, 0.6) at strength 40, i.e. KHR_materials_emissive_strength) behind a
  diffuser box open towards the wall (front and four sides, white, alpha 0.5);
- a perspective camera at 1.4 m height (the panorama comparisons only use its position).
Every material is a Principled BSDF (base colour, roughness, alpha, emission) with backface
culling off (glTF doubleSided). The glass, fabric and diffuser materials have blend_method
'BLEND' (shadow_method 'HASHED'), which the exporter writes as alphaMode BLEND with the
Principled Alpha input in baseColorFactor[3]. The exporter writes the lights in its default
"Standard" units: point cd = W / (4 pi) * 683. The script re-reads the written file, checks
the alpha modes and prints the lights, the materials, the camera position in glTF
coordinates and the triangle count.
"""
import argparse
import json
import math
import os
import sys

import bpy
from mathutils import Euler, Vector

# The geometry helpers of the lit room, shared (the folder is on sys.path when Blender runs us).
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from make_lit_room import add_object, assign, box, cylinder, lathe, uv_sphere  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DEFAULT_OUT = os.path.join(ROOT, "tests", "data", "gltf", "blender_glass_lamp", "glass_lamp_room.gltf")

# Room (inside faces) and wall thickness, metres.
ROOM_X, ROOM_Y, ROOM_Z = 2.0, 1.5, 2.6
WALL = 0.1
# Table (centre, top height) and the lamps.
TABLE = (0.8, 0.3, 0.75)
GLOBE_CENTRE = (1.05, 0.45, TABLE[2] + 0.36)
GLOBE_RADIUS = 0.12
PENDANT = (-0.9, -0.2)          # x, y of the pendant's axis
PENDANT_LIGHT_Z = 1.85
SCONCE = (-0.5, 1.7)            # x, z of the sconce's centre on the north wall
CAMERA = (-0.2, -0.6, 1.4)      # Blender coordinates
# Blended materials: name -> alpha (checked against the written file).
BLENDED = {"globe_glass": 0.35, "shade_fabric": 0.6, "diffuser": 0.5}


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="make_glass_lamp_room.py")
    p.add_argument("--out", default=DEFAULT_OUT, help="output .gltf (a .bin is written beside it)")
    return p.parse_args(argv)


# ---------------------------------------------------------------------------------------
# Geometry: parts are (vertices, faces) with faces wound counter-clockwise seen from outside.

def diffuser_box(cx, y_wall, cz, half_w, half_h, depth):
    """Front and four sides of a box standing out of the wall y = y_wall towards -y; open at the wall."""
    y1 = y_wall - depth
    x0, x1, z0, z1 = cx - half_w, cx + half_w, cz - half_h, cz + half_h
    v = [(x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1),                      # front corners
         (x0, y_wall, z0), (x1, y_wall, z0), (x1, y_wall, z1), (x0, y_wall, z1)]      # at the wall
    f = [(0, 1, 2, 3),            # front, facing -y
         (4, 5, 1, 0),            # bottom, facing -z
         (3, 2, 6, 7),            # top, facing +z
         (0, 3, 7, 4),            # west, facing -x
         (1, 5, 6, 2)]            # east, facing +x
    return v, f


def make_mesh(name, parts, smooth=False):
    verts, faces = [], []
    for pv, pf in parts:
        offset = len(verts)
        verts += pv
        faces += [tuple(i + offset for i in face) for face in pf]
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    mesh.validate()
    if smooth:
        for poly in mesh.polygons:
            poly.use_smooth = True
        mesh.use_auto_smooth = True
        mesh.auto_smooth_angle = math.radians(60)
    mesh.update()
    return mesh


# ---------------------------------------------------------------------------------------
# Materials: Principled BSDF; blended ones with the Alpha input and blend_method BLEND.

def principled(name, colour, roughness, alpha=1.0, emission=None, strength=0.0):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    mat.use_backface_culling = False      # glTF doubleSided
    node = mat.node_tree.nodes["Principled BSDF"]
    node.inputs["Base Color"].default_value = (*colour, 1.0)
    node.inputs["Metallic"].default_value = 0.0
    node.inputs["Roughness"].default_value = roughness
    node.inputs["Alpha"].default_value = alpha
    if emission is not None:
        node.inputs["Emission"].default_value = (*emission, 1.0)
        node.inputs["Emission Strength"].default_value = strength
    if alpha < 1.0:
        mat.blend_method = "BLEND"        # the exporter writes BLEND or HASHED as alphaMode BLEND
        mat.shadow_method = "HASHED"
        mat.show_transparent_back = True
    return mat


# ---------------------------------------------------------------------------------------
# The room.

def build_shell(materials):
    x, y, z, t = ROOM_X, ROOM_Y, ROOM_Z, WALL
    assign(add_object("floor", make_mesh("floor", [box(-x - t, x + t, -y - t, y + t, -t, 0.0)])), materials["floor"])
    assign(add_object("ceiling", make_mesh("ceiling", [box(-x - t, x + t, -y - t, y + t, z, z + t)])), materials["ceiling"])
    walls = [box(-x - t, x + t, y, y + t, 0.0, z),      # north (+y)
             box(-x - t, x + t, -y - t, -y, 0.0, z),    # south (-y)
             box(x, x + t, -y, y, 0.0, z),              # east (+x)
             box(-x - t, -x, -y, y, 0.0, z)]            # west (-x)
    assign(add_object("walls", make_mesh("walls", walls)), materials["wall"])


def build_furniture(materials):
    cx, cy, top = TABLE
    half_x, half_y = 0.6, 0.35
    parts = [box(cx - half_x, cx + half_x, cy - half_y, cy + half_y, top - 0.04, top)]
    for sx in (-1, 1):
        for sy in (-1, 1):
            parts.append(cylinder(cx + sx * (half_x - 0.07), cy + sy * (half_y - 0.07), 0.03, 0.0, top - 0.04, 16))
    assign(add_object("table", make_mesh("table", parts)), materials["table"])
    # A low cabinet against the west wall, under the pendant's light.
    cabinet = box(-ROOM_X + 0.01, -ROOM_X + 0.46, -1.2, 0.0, 0.0, 0.8)
    assign(add_object("cabinet", make_mesh("cabinet", [cabinet])), materials["cabinet"])


def build_table_lamp(materials):
    gx, gy, gz = GLOBE_CENTRE
    bottom = gz - GLOBE_RADIUS
    parts = [cylinder(gx, gy, 0.08, TABLE[2], TABLE[2] + 0.025, 24),        # base
             cylinder(gx, gy, 0.012, TABLE[2] + 0.025, bottom - 0.005, 12)]  # stem, 5 mm below the glass
    assign(add_object("lamp_base", make_mesh("lamp_base", parts)), materials["lamp_metal_dark"])
    globe = add_object("glass_globe", make_mesh("glass_globe", [uv_sphere(gx, gy, gz, GLOBE_RADIUS)], smooth=True))
    assign(globe, materials["globe_glass"])
    add_light("table_lamp", 40.0, GLOBE_CENTRE, (1.0, 0.88, 0.72))


def build_pendant(materials):
    px, py = PENDANT
    shade_z0, shade_z1 = PENDANT_LIGHT_Z - 0.12, PENDANT_LIGHT_Z + 0.12
    # The socket 5 cm above the light: its shadow on the ceiling, a cone of half-angle 17 degrees,
    # stays inside the cone of the shade's top opening (43 degrees), which lights a ring of ceiling.
    parts = [cylinder(px, py, 0.006, shade_z1 + 0.03, ROOM_Z, 8),           # cord
             cylinder(px, py, 0.015, PENDANT_LIGHT_Z + 0.05, shade_z1 + 0.03, 16)]  # socket
    assign(add_object("pendant_cord", make_mesh("pendant_cord", parts)), materials["lamp_metal_dark"])
    profile = [(0.22, shade_z0), (0.18, 0.5 * (shade_z0 + shade_z1)), (0.11, shade_z1)]
    shade = add_object("lampshade", make_mesh("lampshade", [lathe(profile, px, py, closed=False)], smooth=True))
    assign(shade, materials["shade_fabric"])
    add_light("pendant_lamp", 60.0, (px, py, PENDANT_LIGHT_Z), (1.0, 1.0, 1.0))


def build_sconce(materials):
    sx, sz = SCONCE
    bulb = add_object("sconce_bulb", make_mesh("sconce_bulb", [uv_sphere(sx, ROOM_Y - 0.09, sz, 0.05, 24, 12)], smooth=True))
    assign(bulb, materials["bulb"])
    panel = add_object("sconce_diffuser", make_mesh("sconce_diffuser", [diffuser_box(sx, ROOM_Y - 0.001, sz, 0.16, 0.12, 0.18)]))
    assign(panel, materials["diffuser"])


def add_light(name, energy, location, colour):
    data = bpy.data.lights.new(name, "POINT")
    data.energy = energy
    data.color = colour
    data.shadow_soft_size = 0.0      # delta light
    return add_object(name, data, location)


def build_camera():
    data = bpy.data.cameras.new("camera")
    data.lens_unit = "FOV"
    data.angle = math.radians(80.0)
    data.clip_start = 0.05
    data.clip_end = 100.0
    position = Vector(CAMERA)
    cam = add_object("camera", data, position)
    target = Vector((0.2, 0.3, 1.3))
    cam.rotation_euler = (target - position).normalized().to_track_quat("-Z", "Y").to_euler()
    bpy.context.scene.camera = cam


def build_scene():
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.context.scene.render.engine = "CYCLES"
    materials = {
        "wall": principled("wall_offwhite", (0.78, 0.76, 0.72), 0.9),
        "ceiling": principled("ceiling_white", (0.85, 0.85, 0.83), 0.9),
        "floor": principled("floor_bluegrey", (0.28, 0.36, 0.44), 0.8),
        "table": principled("table_oak", (0.45, 0.29, 0.15), 0.6),
        "cabinet": principled("cabinet_green", (0.20, 0.35, 0.25), 0.7),
        "lamp_metal_dark": principled("lamp_dark", (0.05, 0.05, 0.05), 0.5),
        "globe_glass": principled("globe_glass", (0.95, 0.95, 0.93), 0.35, alpha=BLENDED["globe_glass"]),
        "shade_fabric": principled("shade_fabric", (0.85, 0.55, 0.25), 0.9, alpha=BLENDED["shade_fabric"]),
        "diffuser": principled("diffuser", (0.9, 0.9, 0.9), 0.8, alpha=BLENDED["diffuser"]),
        "bulb": principled("bulb", (1.0, 1.0, 1.0), 0.5, emission=(1.0, 0.85, 0.6), strength=40.0),
    }
    build_shell(materials)
    build_furniture(materials)
    build_table_lamp(materials)
    build_pendant(materials)
    build_sconce(materials)
    build_camera()


def export(path):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    bpy.ops.export_scene.gltf(
        filepath=path, export_format="GLTF_SEPARATE", export_yup=True, export_lights=True,
        export_cameras=True, export_apply=True, export_texcoords=False, export_normals=True,
        export_tangents=False, export_colors=False, export_materials="EXPORT", export_animations=False,
        export_extras=False, export_draco_mesh_compression_enable=False, convert_lighting_mode="SPEC")


def summarise(path):
    """Re-reads the written glTF, checks the blended materials and prints what a loader will see."""
    with open(path) as f:
        doc = json.load(f)
    print("extensionsUsed:", doc.get("extensionsUsed"))
    lights = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    nodes = doc["nodes"]
    for n in nodes:
        if "KHR_lights_punctual" in n.get("extensions", {}):
            light = lights[n["extensions"]["KHR_lights_punctual"]["light"]]
            print(f"light node '{n['name']}': {light['type']} intensity {light.get('intensity', 1.0):.4f} cd"
                  f" colour {light.get('color')} translation {n.get('translation')}")
    problems = []
    for m in doc.get("materials", []):
        pbr = m.get("pbrMetallicRoughness", {})
        alpha = pbr.get("baseColorFactor", [1, 1, 1, 1])[3]
        extra = ""
        if "emissiveFactor" in m:
            extra = f" emissive {m['emissiveFactor']} x {m.get('extensions', {}).get('KHR_materials_emissive_strength', {}).get('emissiveStrength', 1.0)}"
        print(f"material '{m['name']}': alphaMode {m.get('alphaMode', 'OPAQUE')} alpha {alpha:.3f}"
              f" doubleSided {m.get('doubleSided', False)} base {pbr.get('baseColorFactor')}"
              f" roughness {pbr.get('roughnessFactor', 1.0)}{extra}")
        if m["name"] in BLENDED and (m.get("alphaMode") != "BLEND" or abs(alpha - BLENDED[m["name"]]) > 1e-6):
            problems.append(f"{m['name']}: alphaMode {m.get('alphaMode')} alpha {alpha}, expected BLEND {BLENDED[m['name']]}")
        if m["name"] not in BLENDED and m.get("alphaMode", "OPAQUE") != "OPAQUE":
            problems.append(f"{m['name']}: alphaMode {m.get('alphaMode')}, expected OPAQUE")
    if len(problems) or sorted(m["name"] for m in doc["materials"] if m.get("alphaMode") == "BLEND") != sorted(BLENDED):
        sys.exit("make_glass_lamp_room.py: " + "; ".join(problems or ["the blended materials are not " + ", ".join(BLENDED)]))
    for n in nodes:
        if "camera" in n:
            t = n.get("translation")
            print(f"camera node '{n['name']}': translation (glTF, +Y up) {t}; "
                  f"--camera={t[0]:.4g},{t[1]:.4g},{t[2]:.4g}")
    triangles = 0
    for n in nodes:
        if "mesh" in n:
            for prim in doc["meshes"][n["mesh"]]["primitives"]:
                triangles += doc["accessors"][prim["indices"]]["count"] // 3
    size = os.path.getsize(path) + sum(os.path.getsize(os.path.join(os.path.dirname(path), b["uri"]))
                                       for b in doc.get("buffers", []) if "uri" in b)
    print(f"meshes {len(doc['meshes'])}, mesh nodes {sum('mesh' in n for n in nodes)}, "
          f"materials {len(doc.get('materials', []))} ({len(BLENDED)} BLEND), lights {len(lights)}, "
          f"triangles {triangles}, {size} bytes")


def main():
    args = parse_args()
    out = os.path.abspath(args.out)
    build_scene()
    export(out)
    summarise(out)


main()

"""Builds a small furnished, lit room in Blender from nothing and exports it as glTF.

The real-world test asset of issue 22: modelled in Blender, written by Blender's own glTF
exporter (io_scene_gltf2), with KHR_lights_punctual lights. Run with a factory startup:

    blender -b --factory-startup --python-exit-code 1 \
        --python scripts/blender/make_lit_room.py -- [--out tests/data/gltf/blender_lit_room/lit_room.gltf]

What it builds (Blender coordinates, +Z up, metres; glTF (x, y, z) = Blender (x, z, -y)):
- a closed room, inside 5 x 4 x 2.7 m (x in [-2.5, 2.5], y in [-2, 2], z in [0, 2.7]),
  walls, floor and ceiling as boxes 0.15 m thick, with a 1.4 x 1.2 m window opening (a hole
  through the west wall, x = -2.5, no glass);
- a table, four chairs sharing one mesh datablock (linked duplicates), a bookcase with
  books, a polished gold sphere (metallic 1, roughness 0.2), a rough copper vase
  (metallic 1, roughness 0.55), a pendant cord; a wooden floor whose base colour, roughness
  and normal maps (256 x 256) are generated here;
- lights with radius 0 (delta lights): a 60 W point light above the table, a 150 W spot
  aimed at the bookcase (spot_size 50 degrees, spot_blend 0.15), a 5 W/m^2 sun shining
  through the window onto the floor (angle 0);
- a perspective camera at 1.5 m height.
Materials are Principled BSDF with base colour, metallic, roughness (and the floor's maps)
only. Only the floor has UVs, and its tangents (Blender's MikkTSpace, as Cycles uses) are
exported for its normal map. The exporter writes the lights in its default "Standard" units: point and spot
cd = W / (4 pi) * 683, sun lx = W/m^2 * 683. The script re-reads the written file and
prints the lights, the camera position in glTF coordinates and the triangle count.
"""
import argparse
import json
import math
import os
import sys

import bpy
import numpy
from mathutils import Euler, Vector

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DEFAULT_OUT = os.path.join(ROOT, "tests", "data", "gltf", "blender_lit_room", "lit_room.gltf")

# Room (inside faces) and wall thickness, metres.
ROOM_X, ROOM_Y, ROOM_Z = 2.5, 2.0, 2.7
WALL = 0.15
# Window opening in the west wall (x = -ROOM_X): y and z ranges.
WINDOW_Y = (-0.7, 0.7)
WINDOW_Z = (0.9, 2.1)
TEXTURE_SIZE = 256
FLOOR_TILE_METRES = 1.0  # one texture tile per metre; 4 planks of 0.25 m per tile


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="make_lit_room.py")
    p.add_argument("--out", default=DEFAULT_OUT, help="output .gltf (a .bin and PNGs are written beside it)")
    return p.parse_args(argv)


# ---------------------------------------------------------------------------------------
# Geometry: parts are (vertices, faces) with faces wound counter-clockwise seen from outside.

def box(x0, x1, y0, y1, z0, z1):
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    f = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    return v, f


def cylinder(cx, cy, radius, z0, z1, segments=12):
    v = []
    for z in (z0, z1):
        for i in range(segments):
            a = 2 * math.pi * i / segments
            v.append((cx + radius * math.cos(a), cy + radius * math.sin(a), z))
    n = segments
    f = [(i, (i + 1) % n, n + (i + 1) % n, n + i) for i in range(n)]
    f.append(tuple(reversed(range(n))))       # bottom, facing -z
    f.append(tuple(range(n, 2 * n)))          # top, facing +z
    return v, f


def lathe(profile, cx, cy, segments=48, closed=True):
    """Surface of revolution of (radius, z) points, bottom to top; closed at the bottom, or
    open at both ends (one sheet)."""
    v = []
    for r, z in profile:
        for i in range(segments):
            a = 2 * math.pi * i / segments
            v.append((cx + r * math.cos(a), cy + r * math.sin(a), z))
    f = []
    for k in range(len(profile) - 1):
        base, up = k * segments, (k + 1) * segments
        for i in range(segments):
            j = (i + 1) % segments
            f.append((base + i, base + j, up + j, up + i))
    if closed:
        f.append(tuple(reversed(range(segments))))  # bottom cap
    return v, f


def uv_sphere(cx, cy, cz, radius, segments=48, rings=24):
    v = [(cx, cy, cz - radius)]
    for k in range(1, rings):
        theta = math.pi * k / rings - math.pi / 2
        for i in range(segments):
            a = 2 * math.pi * i / segments
            v.append((cx + radius * math.cos(theta) * math.cos(a),
                      cy + radius * math.cos(theta) * math.sin(a),
                      cz + radius * math.sin(theta)))
    v.append((cx, cy, cz + radius))
    top = len(v) - 1
    f = [(0, 1 + (i + 1) % segments, 1 + i) for i in range(segments)]
    for k in range(rings - 2):
        base, up = 1 + k * segments, 1 + (k + 1) * segments
        for i in range(segments):
            j = (i + 1) % segments
            f.append((base + i, base + j, up + j, up + i))
    last = 1 + (rings - 2) * segments
    f += [(last + i, last + (i + 1) % segments, top) for i in range(segments)]
    return v, f


def make_mesh(name, parts, smooth=False, uvs=False):
    """One mesh datablock from parts; with uvs, box-projected UVs (metres / FLOOR_TILE_METRES)."""
    verts, faces = [], []
    for pv, pf in parts:
        offset = len(verts)
        verts += pv
        faces += [tuple(i + offset for i in face) for face in pf]
    mesh = bpy.data.meshes.new(name)
    mesh.from_pydata(verts, [], faces)
    mesh.validate()
    if uvs:  # only textured meshes: the exporter writes TEXCOORD_0 for every UV layer
        uv = mesh.uv_layers.new(name="UVMap")
        for poly in mesh.polygons:
            axis = max(range(3), key=lambda a: abs(poly.normal[a]))
            u_axis, v_axis = [a for a in range(3) if a != axis]
            for li in poly.loop_indices:
                co = mesh.vertices[mesh.loops[li].vertex_index].co
                uv.data[li].uv = (co[u_axis] / FLOOR_TILE_METRES, co[v_axis] / FLOOR_TILE_METRES)
    if smooth:
        for poly in mesh.polygons:
            poly.use_smooth = True
        mesh.use_auto_smooth = True
        mesh.auto_smooth_angle = math.radians(40)
    mesh.update()
    return mesh


def add_object(name, data, location=(0, 0, 0), rotation_z_degrees=0.0):
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    obj.rotation_euler = Euler((0, 0, math.radians(rotation_z_degrees)))
    bpy.context.scene.collection.objects.link(obj)
    return obj


# ---------------------------------------------------------------------------------------
# Textures: a wooden floor (planks along x), its roughness and normal maps.

def floor_textures(size):
    """Returns (colour sRGB, roughness, normal) as float arrays [row (v up), column (u), 4]."""
    rng = numpy.random.default_rng(22)
    planks = 4
    plank_px = size // planks
    u = numpy.arange(size)[None, :].repeat(size, 0).astype(float)
    v = numpy.arange(size)[:, None].repeat(size, 1).astype(float)
    row = (v // plank_px).astype(int)
    # Each plank row has one end joint, staggered, and its own tone.
    joint = numpy.array([0.15, 0.65, 0.35, 0.85])[row] * size
    tone = numpy.array([1.0, 0.86, 0.95, 0.8])[row]
    du = numpy.minimum(numpy.abs(u - joint), size - numpy.abs(u - joint))
    dv = numpy.minimum(v % plank_px, plank_px - 1 - (v % plank_px))
    groove = numpy.clip(numpy.minimum(du, dv) / 1.5, 0.0, 1.0)  # 0 in the 2-3 px gaps
    # Grain: stretched noise along u, wavy stripes across v.
    noise = rng.normal(size=(size, size // 8 + 2))
    noise = numpy.repeat(noise, 8, axis=1)[:, :size]
    kernel = numpy.ones(9) / 9
    noise = numpy.apply_along_axis(lambda r: numpy.convolve(r, kernel, mode="same"), 1, noise)
    stripes = 0.5 + 0.5 * numpy.sin(v * 0.9 + 3.0 * numpy.sin(u * 2 * math.pi / size + row) + noise * 1.2)
    grain = 0.82 + 0.18 * stripes
    base = numpy.array([0.62, 0.42, 0.24])  # sRGB oak
    colour = base[None, None, :] * (tone * grain)[..., None] * (0.35 + 0.65 * groove)[..., None]
    rough = numpy.clip(0.5 + 0.12 * (1 - stripes) + 0.3 * (1 - groove), 0.0, 1.0)
    height = groove * (1 + 0.02 * stripes)
    # Normal in tangent space (+x along u, +y along v up), OpenGL convention as glTF.
    strength = 2.0
    dh_du = numpy.gradient(height, axis=1) * strength
    dh_dv = numpy.gradient(height, axis=0) * strength
    n = numpy.stack([-dh_du, -dh_dv, numpy.ones_like(height)], axis=-1)
    n /= numpy.linalg.norm(n, axis=-1, keepdims=True)
    ones = numpy.ones((size, size, 1))
    colour_rgba = numpy.concatenate([numpy.clip(colour, 0, 1), ones], axis=-1)
    # glTF metallicRoughness: G roughness, B metallic (0 here); R unused.
    rough_rgba = numpy.stack([numpy.ones_like(rough), rough, numpy.zeros_like(rough), numpy.ones_like(rough)], axis=-1)
    normal_rgba = numpy.concatenate([0.5 * n + 0.5, ones], axis=-1)
    return colour_rgba, rough_rgba, normal_rgba


def make_image(name, pixels, non_colour):
    size = pixels.shape[0]
    # is_data before the pixels: changing the colour space afterwards discards them.
    image = bpy.data.images.new(name, size, size, alpha=False, is_data=non_colour)
    image.pixels.foreach_set(pixels.astype(numpy.float32).ravel())
    image.file_format = "PNG"
    image.pack()  # the exporter writes packed PNGs as they are
    return image


# ---------------------------------------------------------------------------------------
# Materials: Principled BSDF, base colour / metallic / roughness only.

def principled(name, colour, roughness, metallic=0.0):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    node = mat.node_tree.nodes["Principled BSDF"]
    node.inputs["Base Color"].default_value = (*colour, 1.0)
    node.inputs["Metallic"].default_value = metallic
    node.inputs["Roughness"].default_value = roughness
    return mat


def floor_material(images):
    colour, rough, normal = images
    mat = principled("floor_wood", (1.0, 1.0, 1.0), 1.0)
    tree = mat.node_tree
    node = tree.nodes["Principled BSDF"]
    tex_colour = tree.nodes.new("ShaderNodeTexImage")
    tex_colour.image = colour
    tree.links.new(tex_colour.outputs["Color"], node.inputs["Base Color"])
    tex_rough = tree.nodes.new("ShaderNodeTexImage")
    tex_rough.image = rough
    separate = tree.nodes.new("ShaderNodeSeparateColor")
    tree.links.new(tex_rough.outputs["Color"], separate.inputs["Color"])
    tree.links.new(separate.outputs["Green"], node.inputs["Roughness"])
    tex_normal = tree.nodes.new("ShaderNodeTexImage")
    tex_normal.image = normal
    normal_map = tree.nodes.new("ShaderNodeNormalMap")
    tree.links.new(tex_normal.outputs["Color"], normal_map.inputs["Color"])
    tree.links.new(normal_map.outputs["Normal"], node.inputs["Normal"])
    return mat


def assign(obj, material):
    obj.data.materials.clear()
    obj.data.materials.append(material)


# ---------------------------------------------------------------------------------------
# The room.

def build_shell(materials):
    x, y, z, t = ROOM_X, ROOM_Y, ROOM_Z, WALL
    floor = add_object("floor", make_mesh("floor", [box(-x - t, x + t, -y - t, y + t, -t, 0.0)], uvs=True))
    assign(floor, materials["floor"])
    ceiling = add_object("ceiling", make_mesh("ceiling", [box(-x - t, x + t, -y - t, y + t, z, z + t)]))
    assign(ceiling, materials["ceiling"])
    (wy0, wy1), (wz0, wz1) = WINDOW_Y, WINDOW_Z
    walls = [
        box(-x - t, x + t, y, y + t, 0.0, z),        # north (+y)
        box(-x - t, x + t, -y - t, -y, 0.0, z),      # south (-y)
        box(x, x + t, -y, y, 0.0, z),                # east (+x)
        # west (-x), four boxes around the window opening
        box(-x - t, -x, -y, wy0, 0.0, z),
        box(-x - t, -x, wy1, y, 0.0, z),
        box(-x - t, -x, wy0, wy1, 0.0, wz0),
        box(-x - t, -x, wy0, wy1, wz1, z),
    ]
    wall_obj = add_object("walls", make_mesh("walls", walls))
    assign(wall_obj, materials["wall"])


def build_table(materials, cx, cy):
    top_z, half_x, half_y = 0.75, 0.7, 0.4
    parts = [box(-half_x, half_x, -half_y, half_y, top_z - 0.04, top_z)]
    for sx in (-1, 1):
        for sy in (-1, 1):
            parts.append(cylinder(sx * (half_x - 0.08), sy * (half_y - 0.08), 0.03, 0.0, top_z - 0.04, 16))
    table = add_object("table", make_mesh("table", parts), (cx, cy, 0.0))
    assign(table, materials["table"])
    return top_z


def chair_mesh():
    seat_z, half = 0.45, 0.21
    parts = [box(-half, half, -half, half, seat_z - 0.04, seat_z)]
    for sx in (-1, 1):
        for sy in (-1, 1):
            parts.append(cylinder(sx * (half - 0.03), sy * (half - 0.03), 0.018, 0.0, seat_z - 0.04, 12))
    # Backrest on the -y side: two posts and two rails.
    parts.append(box(-half, -half + 0.03, -half, -half + 0.03, seat_z, seat_z + 0.45))
    parts.append(box(half - 0.03, half, -half, -half + 0.03, seat_z, seat_z + 0.45))
    parts.append(box(-half, half, -half, -half + 0.025, seat_z + 0.30, seat_z + 0.45))
    parts.append(box(-half, half, -half, -half + 0.025, seat_z + 0.12, seat_z + 0.18))
    return make_mesh("chair", parts)


def build_chairs(materials, table_x, table_y):
    mesh = chair_mesh()
    mesh.materials.append(materials["chair"])
    # (dx, dy, yaw): backrest away from the table; one chair pulled out and turned.
    placements = [(-0.35, -0.62, 0.0), (0.35, -0.68, 8.0), (-0.35, 0.62, 180.0), (0.45, 0.80, 200.0)]
    chairs = []
    for k, (dx, dy, yaw) in enumerate(placements):
        chairs.append(add_object(f"chair_{k}", mesh, (table_x + dx, table_y + dy, 0.0), yaw))
    assert all(c.data == mesh for c in chairs)
    return chairs


def build_bookcase(materials):
    x0, x1 = ROOM_X - 0.36, ROOM_X - 0.01      # depth along x, against the east wall
    y0, y1 = -1.6, -0.4
    height, board = 1.8, 0.025
    parts = [box(x0, x1, y0, y0 + board, 0.0, height), box(x0, x1, y1 - board, y1, 0.0, height),
             box(x1 - board, x1, y0, y1, 0.0, height)]
    shelves = [0.05, 0.48, 0.91, 1.34, height - board]
    for z in shelves:
        parts.append(box(x0, x1 - board, y0 + board, y1 - board, z, z + board))
    case = add_object("bookcase", make_mesh("bookcase", parts))
    assign(case, materials["bookcase"])
    # Books on the three lower shelves, deterministic widths and heights.
    rng = numpy.random.default_rng(7)
    book_parts = {"book_red": [], "book_blue": [], "book_cream": []}
    names = list(book_parts)
    for shelf in shelves[:3]:
        y = y0 + board + 0.02
        z = shelf + board
        while True:
            w = float(rng.uniform(0.025, 0.05))
            h = float(rng.uniform(0.22, 0.34))
            d = float(rng.uniform(0.17, 0.24))
            if y + w > y1 - board - 0.25:   # leave room at the end of each shelf
                break
            book_parts[names[int(rng.integers(0, 3))]].append(box(x1 - board - d - 0.01, x1 - board - 0.01, y, y + w, z, z + h))
            y += w + 0.004
    for name, parts_of in book_parts.items():
        if parts_of:
            books = add_object(name, make_mesh(name, parts_of))
            assign(books, materials[name])


def build_props(materials, table_x, table_y, table_top):
    sphere = add_object("gold_sphere", make_mesh("gold_sphere", [uv_sphere(0.0, 0.0, 0.12, 0.12)], smooth=True),
                        (table_x - 0.3, table_y - 0.1, table_top))
    assign(sphere, materials["gold"])
    profile = [(0.09, 0.0), (0.13, 0.04), (0.16, 0.14), (0.165, 0.22), (0.15, 0.30),
               (0.10, 0.38), (0.075, 0.44), (0.08, 0.48), (0.095, 0.50), (0.085, 0.505)]
    vase = add_object("copper_vase", make_mesh("copper_vase", [lathe(profile, 0.0, 0.0)], smooth=True),
                      (ROOM_X - 0.35, 0.9, 0.0))
    assign(vase, materials["copper"])
    cord = add_object("lamp_cord", make_mesh("lamp_cord", [cylinder(0.0, 0.0, 0.006, 1.62, ROOM_Z, 8)]),
                      (table_x, table_y, 0.0))
    assign(cord, materials["cord"])


def look_rotation(direction):
    """Rotation that turns a light's or camera's local -Z onto direction (local +Y up)."""
    return Vector(direction).normalized().to_track_quat("-Z", "Y").to_euler()


def add_light(name, kind, energy, location, direction=None, **extra):
    data = bpy.data.lights.new(name, kind)
    data.energy = energy
    data.color = (1.0, 1.0, 1.0)
    if kind == "SUN":
        data.angle = 0.0                 # delta light
    else:
        data.shadow_soft_size = 0.0      # delta light
    for key, value in extra.items():
        setattr(data, key, value)
    obj = add_object(name, data, location)
    if direction is not None:
        obj.rotation_euler = look_rotation(direction)
    return obj


def sun_direction():
    """Sunlight travel direction: from the west (+x), 40 degrees elevation, 15 degrees azimuth."""
    elevation, azimuth = math.radians(40), math.radians(15)
    return Vector((math.cos(elevation) * math.cos(azimuth), math.cos(elevation) * math.sin(azimuth), -math.sin(elevation)))


def build_lights(table_x, table_y):
    add_light("lamp_point", "POINT", 60.0, (table_x, table_y, 1.55))
    spot_pos = Vector((0.9, -1.0, 2.6))
    spot_target = Vector((ROOM_X - 0.2, -1.0, 1.0))
    add_light("spot", "SPOT", 150.0, spot_pos, spot_target - spot_pos,
              spot_size=math.radians(50.0), spot_blend=0.15, show_cone=True)
    # The sun object's position does not matter; place it outside the window.
    add_light("sun", "SUN", 5.0, (-ROOM_X - 2.0, 0.0, 3.5), sun_direction())


def build_camera(table_x, table_y):
    data = bpy.data.cameras.new("camera")
    data.lens_unit = "FOV"
    data.angle = math.radians(75.0)
    data.clip_start = 0.05
    data.clip_end = 100.0
    position = Vector((-1.2, -1.2, 1.5))
    cam = add_object("camera", data, position)
    cam.rotation_euler = look_rotation(Vector((table_x, table_y, 0.8)) - position)
    bpy.context.scene.camera = cam
    return cam


def build_scene(out_dir):
    bpy.ops.wm.read_factory_settings(use_empty=True)
    scene = bpy.context.scene
    scene.render.engine = "CYCLES"
    images = [make_image(name, pixels, non_colour)
              for name, pixels, non_colour in zip(("floor_basecolor", "floor_roughness", "floor_normal"),
                                                  floor_textures(TEXTURE_SIZE), (False, True, True))]
    materials = {
        "floor": floor_material(images),
        "wall": principled("wall_plaster", (0.75, 0.73, 0.68), 0.9),
        "ceiling": principled("ceiling_white", (0.82, 0.82, 0.80), 0.9),
        "table": principled("table_walnut", (0.30, 0.17, 0.09), 0.45),
        "chair": principled("chair_blue_paint", (0.12, 0.25, 0.42), 0.6),
        "bookcase": principled("bookcase_pine", (0.62, 0.50, 0.36), 0.7),
        "book_red": principled("book_red", (0.55, 0.08, 0.06), 0.8),
        "book_blue": principled("book_blue", (0.08, 0.15, 0.45), 0.8),
        "book_cream": principled("book_cream", (0.80, 0.74, 0.58), 0.8),
        "gold": principled("gold_polished", (1.0, 0.77, 0.34), 0.2, metallic=1.0),
        "copper": principled("copper_rough", (0.95, 0.64, 0.54), 0.55, metallic=1.0),
        "cord": principled("cord_black", (0.03, 0.03, 0.03), 0.5),
    }
    table_x, table_y = 0.6, 0.4
    build_shell(materials)
    table_top = build_table(materials, table_x, table_y)
    build_chairs(materials, table_x, table_y)
    build_bookcase(materials)
    build_props(materials, table_x, table_y, table_top)
    build_lights(table_x, table_y)
    build_camera(table_x, table_y)


def export(path):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    bpy.ops.export_scene.gltf(
        filepath=path, export_format="GLTF_SEPARATE", export_texture_dir="", export_image_format="AUTO",
        export_yup=True, export_lights=True, export_cameras=True, export_apply=True,
        export_texcoords=True, export_normals=True, export_tangents=True, export_colors=False,
        export_materials="EXPORT", export_animations=False, export_extras=False,
        export_draco_mesh_compression_enable=False, convert_lighting_mode="SPEC")


def summarise(path):
    """Re-reads the written glTF and prints what a loader will see."""
    with open(path) as f:
        doc = json.load(f)
    lights = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    print("extensionsUsed:", doc.get("extensionsUsed"))
    print("extensionsRequired:", doc.get("extensionsRequired"))
    if "KHR_lights_punctual" not in doc.get("extensionsRequired", []):
        sys.exit("make_lit_room.py: KHR_lights_punctual is not in extensionsRequired")
    nodes = doc["nodes"]
    light_nodes = [n for n in nodes if "KHR_lights_punctual" in n.get("extensions", {})]
    if len(light_nodes) != len(lights) or len(lights) != 3:
        sys.exit(f"make_lit_room.py: {len(lights)} lights, {len(light_nodes)} light nodes, expected 3 and 3")
    for n in light_nodes:
        light = lights[n["extensions"]["KHR_lights_punctual"]["light"]]
        unit = "lx" if light["type"] == "directional" else "cd"
        print(f"light node '{n['name']}': {light['type']} intensity {light.get('intensity', 1.0):.4f} {unit}"
              f" spot {light.get('spot')} translation {n.get('translation')} rotation {n.get('rotation')}")
    for n in nodes:
        if "camera" in n:
            print(f"camera node '{n['name']}': translation (glTF, +Y up) {n.get('translation')} rotation {n.get('rotation')}")
    triangles = 0
    for n in nodes:
        if "mesh" in n:
            for prim in doc["meshes"][n["mesh"]]["primitives"]:
                triangles += doc["accessors"][prim["indices"]]["count"] // 3
    print(f"meshes {len(doc['meshes'])}, mesh nodes {sum('mesh' in n for n in nodes)}, "
          f"materials {len(doc.get('materials', []))}, images {len(doc.get('images', []))}, triangles {triangles}")


def main():
    args = parse_args()
    out = os.path.abspath(args.out)
    build_scene(os.path.dirname(out))
    export(out)
    summarise(out)


if __name__ == "__main__":  # make_glass_lamp_room.py imports its geometry helpers
    main()

"""Builds a large furnished apartment in Blender and exports it as glTF: the scale test of issue 22.

Issue 22 item 6 ("Scale"): a scene of 1-2 million triangles with a few hundred textures, modelled in
Blender and written by Blender's own glTF exporter (io_scene_gltf2, GLTF_SEPARATE,
KHR_lights_punctual). Run with a factory startup; the output is large, keep it out of the repo:

    blender -b --factory-startup --python-exit-code 1 --python scripts/blender/make_big_room.py -- \\
        --out /work/bitcheck/big_room [--triangles 1500000] [--textures 300] [--seed 1] [--texture-size 512]

Writes OUT/big_room.gltf, OUT/big_room.bin, the textures beside them (colour maps JPEG, normal and
roughness maps PNG) and OUT/big_room_summary.json (what the written file holds: triangles drawn and
unique, meshes, nodes, materials, images by size and format, lights, camera, the arguments).

What it builds (Blender coordinates, +Z up, metres; glTF (x, y, z) = Blender (x, z, -y)):
- a 16 x 11 m apartment, 2.8 m high, four rooms: a living room and an open dining room with a
  kitchen (south), a bedroom and a study (north); exterior walls 0.15 m, interior 0.12 m, with
  doors, a wide opening between living and dining room, 9 window openings (no glass) with sills;
- furniture modelled from bevelled and subdivided boxes and cylinders (Blender's Bevel and
  Subdivision Surface modifiers, applied before export): sofas, armchairs, a bed, tables,
  chairs, bar stools, office chairs, desks, sideboards, a wardrobe, bookshelves with books, a
  kitchen with an island, lamps, rugs, framed paintings on the free wall space. Chairs, stools,
  armchairs, nightstands and shelf frames are linked duplicates (one mesh on many nodes);
- decorations (vases, bowls, sculptures, plants) on shelves, tables, sills and the floor,
  sized so that the scene reaches --triangles (within about 0.1%); some are linked duplicates;
- --textures distinct images generated here with numpy (wood, tiles, marble, terrazzo, weave,
  leather, wallpaper, brushed metal, carpets, book covers, abstract paintings; each material its
  own pattern and colours): floors, walls, rugs and paintings at --texture-size, everything
  else at half of it. Some materials also get a normal map and a roughness (metallic) map;
- lights with radius 0 (delta lights): ceiling points in every room, floor and bedside lamps,
  three spots over the kitchen worktop, a sun shining through the south windows;
- one perspective camera in the living room at 1.5 m, looking towards the dining room.
The same arguments give the same scene (one numpy generator seeded by --seed): the same JSON, images
and geometry; exported tangents may differ in the last bit between runs (Blender computes them in threads).
"""
import argparse
import colorsys
import json
import math
import os
import shutil
import sys
import tempfile
import time

import bpy
import numpy as np
from mathutils import Euler, Vector

# Apartment: inner faces of the exterior walls at x = 0, 16 and y = 0, 11; ceiling height.
WIDTH, DEPTH, HEIGHT = 16.0, 11.0, 2.8
EXT = 0.15      # exterior wall thickness
INT_HALF = 0.06  # half the interior wall thickness
WINDOW_Z = (0.9, 2.3)
DOOR_Z = (0.0, 2.1)

# Walls: name, axis the wall runs along, its line, extent along the axis, thickness across it,
# openings (lo, hi, z0, z1) along the axis.
WALLS = [
    ("wall_south", "x", 0.0, (-EXT, WIDTH + EXT), (-EXT, 0.0),
     [(1.5, 3.5, *WINDOW_Z), (5.5, 7.5, *WINDOW_Z), (11.0, 13.5, *WINDOW_Z)]),
    ("wall_north", "x", DEPTH, (-EXT, WIDTH + EXT), (DEPTH, DEPTH + EXT),
     [(4.3, 6.3, *WINDOW_Z), (10.0, 12.5, *WINDOW_Z), (13.5, 15.0, *WINDOW_Z)]),
    ("wall_west", "y", 0.0, (0.0, DEPTH), (-EXT, 0.0), [(2.0, 4.5, *WINDOW_Z)]),
    ("wall_east", "y", WIDTH, (0.0, DEPTH), (WIDTH, WIDTH + EXT), [(2.0, 4.5, *WINDOW_Z), (8.0, 10.0, *WINDOW_Z)]),
    ("wall_hall", "x", 6.5, (0.0, WIDTH), (6.5 - INT_HALF, 6.5 + INT_HALF), [(5.0, 6.0, *DOOR_Z), (11.0, 12.0, *DOOR_Z)]),
    ("wall_living_dining", "y", 9.0, (0.0, 6.5 - INT_HALF), (9.0 - INT_HALF, 9.0 + INT_HALF), [(1.5, 4.5, 0.0, 2.4)]),
    ("wall_bed_study", "y", 7.0, (6.5 + INT_HALF, DEPTH), (7.0 - INT_HALF, 7.0 + INT_HALF), [(7.5, 8.5, *DOOR_Z)]),
]
# Rooms by their inner faces: x0, x1, y0, y1.
ROOMS = {
    "living": (0.0, 9.0 - INT_HALF, 0.0, 6.5 - INT_HALF),
    "dining": (9.0 + INT_HALF, WIDTH, 0.0, 6.5 - INT_HALF),
    "bedroom": (0.0, 7.0 - INT_HALF, 6.5 + INT_HALF, DEPTH),
    "study": (7.0 + INT_HALF, WIDTH, 6.5 + INT_HALF, DEPTH),
}

# Material categories: the maps each material of the category gets, whether its textures are
# large (--texture-size) or half that, and metres per texture repeat (None: the image spans the
# part once, as on a rug or a canvas).
CATEGORIES = {
    "floor": (("colour", "normal", "rough"), True, 1.2),
    "wall": (("colour", "normal"), True, 1.0),
    "rug": (("colour", "normal"), True, None),
    "art": (("colour",), True, None),
    "wood": (("colour", "normal", "rough"), False, 0.7),
    "fabric": (("colour", "normal"), False, 0.35),
    "stone": (("colour", "rough"), False, 0.6),
    "metal": (("colour", "rough"), False, 0.4),
    "ceramic": (("colour",), False, 0.25),
    "paper": (("colour",), False, 0.3),
}
# Categories filled first, one material per request (floors, walls, rugs, paintings).
FIXED = ("floor", "wall", "rug", "art")
PLAIN = {  # untextured materials: sRGB-ish linear colour, roughness, metallic
    "white": ((0.80, 0.80, 0.78), 0.85, 0.0),
    "ceiling": ((0.82, 0.82, 0.80), 0.9, 0.0),
    "black": ((0.02, 0.02, 0.02), 0.4, 0.0),
    "leaf": ((0.06, 0.22, 0.05), 0.6, 0.0),
    "mattress": ((0.75, 0.75, 0.72), 0.9, 0.0),
    "screen": ((0.01, 0.01, 0.012), 0.15, 0.0),
}


def parse_args():
    argv = sys.argv[sys.argv.index("--") + 1:] if "--" in sys.argv else []
    p = argparse.ArgumentParser(prog="make_big_room.py", description=__doc__.split("\n")[0])
    p.add_argument("--out", required=True, help="output folder (big_room.gltf, .bin, textures, summary)")
    p.add_argument("--triangles", type=int, default=1_500_000, help="target triangle count, drawn (default 1500000)")
    p.add_argument("--textures", type=int, default=300, help="distinct images (default 300)")
    p.add_argument("--seed", type=int, default=1, help="random seed (default 1)")
    p.add_argument("--texture-size", type=int, default=512,
                   help="floors, walls, rugs, paintings; other textures are half (default 512)")
    p.add_argument("--name", default="big_room", help="file stem (default big_room)")
    return p.parse_args(argv)


# ---------------------------------------------------------------------------------------
# Geometry. A part is (vertices, faces, slot): faces counter-clockwise seen from outside,
# slot the mesh's material slot.

def box(x0, x1, y0, y1, z0, z1, slot=0):
    v = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
         (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    f = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7)]
    return v, f, slot


def cbox(cx, cy, w, d, z0, z1, slot=0):
    """Box centred on (cx, cy) in plan."""
    return box(cx - w / 2, cx + w / 2, cy - d / 2, cy + d / 2, z0, z1, slot)


def cylinder(p0, p1, radius, segments=12, slot=0):
    """Closed cylinder from p0 to p1."""
    p0, p1 = np.asarray(p0, float), np.asarray(p1, float)
    axis = (p1 - p0) / np.linalg.norm(p1 - p0)
    helper = np.array([1.0, 0.0, 0.0]) if abs(axis[0]) < 0.9 else np.array([0.0, 1.0, 0.0])
    u = np.cross(axis, helper)
    u /= np.linalg.norm(u)
    w = np.cross(axis, u)  # u x w = axis: rings run counter-clockwise around the axis
    v = []
    for end in (p0, p1):
        for i in range(segments):
            a = 2 * math.pi * i / segments
            v.append(tuple(end + radius * (math.cos(a) * u + math.sin(a) * w)))
    n = segments
    f = [(i, (i + 1) % n, n + (i + 1) % n, n + i) for i in range(n)]
    f.append(tuple(reversed(range(n))))
    f.append(tuple(range(n, 2 * n)))
    return v, f, slot


def lathe_part(profile, segments, slot=0, cap_bottom=True, cap_top=False):
    """Surface of revolution about the z axis of (radius, z) points, bottom to top."""
    v = [(r * math.cos(2 * math.pi * i / segments), r * math.sin(2 * math.pi * i / segments), z)
         for r, z in profile for i in range(segments)]
    f = []
    for k in range(len(profile) - 1):
        base, up = k * segments, (k + 1) * segments
        f += [(base + i, base + (i + 1) % segments, up + (i + 1) % segments, up + i) for i in range(segments)]
    if cap_bottom:
        f.append(tuple(reversed(range(segments))))
    if cap_top:
        f.append(tuple(range((len(profile) - 1) * segments, len(profile) * segments)))
    return v, f, slot


def rotated(part, degrees, about=(0.0, 0.0)):
    """The part turned about the vertical axis through `about`."""
    v, f, slot = part
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    ax, ay = about
    return [(ax + c * (x - ax) - s * (y - ay), ay + s * (x - ax) + c * (y - ay), z) for x, y, z in v], f, slot


def tilted(part, degrees, pivot):
    """The part turned about the x axis through pivot (y, z)."""
    v, f, slot = part
    c, s = math.cos(math.radians(degrees)), math.sin(math.radians(degrees))
    py, pz = pivot
    return [(x, py + c * (y - py) - s * (z - pz), pz + s * (y - py) + c * (z - pz)) for x, y, z in v], f, slot


def triangles_of(mesh):
    totals = np.empty(len(mesh.polygons), np.int32)
    mesh.polygons.foreach_get("loop_total", totals)
    return int((totals - 2).sum())


def box_uvs(mesh, tiles):
    """Box-projected UVs: each face along its dominant axis, metres / tiles[slot] (None: the
    slot's faces of each axis span [0, 1])."""
    n_poly = len(mesh.polygons)
    co = np.empty(len(mesh.vertices) * 3, np.float32)
    mesh.vertices.foreach_get("co", co)
    loops = np.empty(len(mesh.loops), np.int32)
    mesh.loops.foreach_get("vertex_index", loops)
    totals = np.empty(n_poly, np.int32)
    mesh.polygons.foreach_get("loop_total", totals)
    normals = np.empty(n_poly * 3, np.float32)
    mesh.polygons.foreach_get("normal", normals)
    slots = np.empty(n_poly, np.int32)
    mesh.polygons.foreach_get("material_index", slots)
    poly_of_loop = np.repeat(np.arange(n_poly), totals)
    axis = np.abs(normals.reshape(-1, 3)).argmax(axis=1)[poly_of_loop]
    p = co.reshape(-1, 3)[loops]
    u = np.where(axis == 0, p[:, 1], p[:, 0])
    v = np.where(axis == 2, p[:, 1], p[:, 2])
    slot_of_loop = slots[poly_of_loop]
    for slot, tile in enumerate(tiles):
        in_slot = slot_of_loop == slot
        if tile is not None:
            u[in_slot] /= tile
            v[in_slot] /= tile
            continue
        for a in range(3):
            sel = in_slot & (axis == a)
            if sel.any():
                u[sel] = (u[sel] - u[sel].min()) / max(float(np.ptp(u[sel])), 1e-6)
                v[sel] = (v[sel] - v[sel].min()) / max(float(np.ptp(v[sel])), 1e-6)
    layer = mesh.uv_layers.new(name="UVMap")
    layer.data.foreach_set("uv", np.stack([u, v], axis=1).astype(np.float32).ravel())


def mesh_from_arrays(name, verts, polys):
    """A mesh from an (n, 3) vertex array and a list of (m, k) index arrays (k-gons)."""
    mesh = bpy.data.meshes.new(name)
    mesh.vertices.add(len(verts))
    mesh.vertices.foreach_set("co", np.asarray(verts, np.float32).ravel())
    flat = np.concatenate([np.asarray(p, np.int32).ravel() for p in polys])
    totals = np.concatenate([np.full(len(p), np.asarray(p).shape[1], np.int32) for p in polys])
    starts = np.concatenate([[0], np.cumsum(totals)[:-1]]).astype(np.int32)
    mesh.loops.add(len(flat))
    mesh.loops.foreach_set("vertex_index", flat)
    mesh.polygons.add(len(totals))
    mesh.polygons.foreach_set("loop_start", starts)
    mesh.polygons.foreach_set("loop_total", totals)
    mesh.update(calc_edges=True)
    return mesh


def smooth(mesh, angle=35.0):
    mesh.polygons.foreach_set("use_smooth", np.ones(len(mesh.polygons), bool))
    mesh.use_auto_smooth = True
    mesh.auto_smooth_angle = math.radians(angle)


# ---------------------------------------------------------------------------------------
# Textures: tileable numpy patterns. Each returns (colour sRGB (S, S, 3), height (S, S),
# roughness (S, S)), rows top to bottom.

def upsample(grid, size):
    """Tileable smoothstep-bilinear interpolation of a random grid to size x size."""
    def axis(n):
        t = np.arange(size) * n / size
        i0 = np.floor(t).astype(int)
        f = t - i0
        return i0 % n, (i0 + 1) % n, f * f * (3 - 2 * f)
    y0, y1, fy = axis(grid.shape[0])
    x0, x1, fx = axis(grid.shape[1])
    fy, fx = fy[:, None], fx[None, :]
    a, b = grid[np.ix_(y0, x0)], grid[np.ix_(y0, x1)]
    c, d = grid[np.ix_(y1, x0)], grid[np.ix_(y1, x1)]
    return (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy


def noise(rng, size, cells_y, cells_x, octaves=3):
    """Tileable value noise in [0, 1]."""
    total, norm, amp = np.zeros((size, size)), 0.0, 1.0
    for _ in range(octaves):
        total += amp * upsample(rng.random((min(cells_y, size), min(cells_x, size))), size)
        norm += amp
        amp *= 0.5
        cells_y, cells_x = cells_y * 2, cells_x * 2
    t = total / norm
    return (t - t.min()) / max(float(np.ptp(t)), 1e-6)


def hsv(h, s, v):
    return np.array(colorsys.hsv_to_rgb(h % 1.0, float(np.clip(s, 0, 1)), float(np.clip(v, 0, 1))))


def coords(size):
    t = (np.arange(size) + 0.5) / size
    return t[None, :].repeat(size, 0), t[:, None].repeat(size, 1)  # u (columns), v (rows)


def wrap_distance(a):
    """Distance to the nearest integer, for tileable joints."""
    return np.abs(a - np.round(a))


def pattern_planks(rng, size, planks=None):
    u, v = coords(size)
    n = int(planks if planks is not None else rng.integers(3, 7))
    row = np.minimum((v * n).astype(int), n - 1)
    grain = noise(rng, size, 48, 3, 3)
    stripes = 0.5 + 0.5 * np.sin(2 * math.pi * v * n * rng.integers(3, 9) + 7 * grain)
    base = hsv(rng.uniform(0.05, 0.11), rng.uniform(0.4, 0.75), rng.uniform(0.35, 0.8))
    tone = rng.uniform(0.8, 1.1, n)[row]
    if planks == 1:
        groove = np.ones_like(u)
    else:
        joint = rng.random(n)[row]
        du = wrap_distance(u - joint) * size
        dv = np.minimum((v * n) % 1.0, 1 - (v * n) % 1.0) * size / n
        groove = np.clip(np.minimum(du, dv) / 1.5, 0, 1)
    colour = base * (tone * (0.78 + 0.22 * stripes) * (0.35 + 0.65 * groove))[..., None]
    return colour, groove * (1 + 0.03 * stripes), 0.45 + 0.15 * (1 - stripes) + 0.3 * (1 - groove)


def pattern_tiles(rng, size, bricks=False):
    u, v = coords(size)
    rows = int(rng.integers(5, 10) if bricks else rng.integers(2, 7))
    cols = int(rng.integers(2, 5)) if bricks else rows
    row = np.minimum((v * rows).astype(int), rows - 1)
    shift = np.where(row % 2 == 1, 0.5 / cols, 0.0) if bricks else 0.0
    uu = (u + shift) * cols
    col = np.floor(uu).astype(int) % cols
    grout = rng.uniform(0.015, 0.05)
    edge = np.minimum(wrap_distance(uu) / cols, wrap_distance(v * rows) / rows)
    mortar = np.clip((edge - grout / 2) * size / 2.0, 0, 1)
    hue, sat = rng.random(), rng.uniform(0.05, 0.6)
    per_tile = rng.uniform(0.75, 1.1, (rows, cols))[row, col]
    base = hsv(hue, sat, rng.uniform(0.45, 0.9)) * (per_tile * (0.9 + 0.1 * noise(rng, size, 16, 16)))[..., None]
    grout_colour = hsv(hue, 0.05, rng.uniform(0.3, 0.8))
    colour = base * mortar[..., None] + grout_colour * (1 - mortar)[..., None]
    return colour, mortar, np.where(mortar > 0.5, rng.uniform(0.15, 0.45), 0.9)


def pattern_marble(rng, size, terrazzo_chips=0):
    u, v = coords(size)
    turbulence = noise(rng, size, 4, 4, 5)
    k = rng.integers(1, 4)
    veins = np.abs(np.sin(2 * math.pi * (k * u + v) + 9 * turbulence))
    light = hsv(rng.random(), rng.uniform(0.0, 0.25), rng.uniform(0.65, 0.95))
    dark = hsv(rng.random(), rng.uniform(0.0, 0.5), rng.uniform(0.05, 0.45))
    t = (1 - veins) ** 6
    colour = light * (1 - t)[..., None] + dark * t[..., None]
    height = 1 - 0.2 * t
    for _ in range(terrazzo_chips):
        cx, cy, r = rng.random() * size, rng.random() * size, rng.uniform(2, 14) * size / 512
        chip = hsv(rng.random(), rng.uniform(0.1, 0.7), rng.uniform(0.2, 0.95))
        lo, hi = int(-r - 1), int(r + 2)
        ys = (np.arange(lo, hi) + int(cy)) % size
        xs = (np.arange(lo, hi) + int(cx)) % size
        dy = (np.arange(lo, hi) + int(cy) - cy)[:, None]
        dx = (np.arange(lo, hi) + int(cx) - cx)[None, :]
        inside = dx * dx + dy * dy <= r * r
        block = colour[np.ix_(ys, xs)]
        block[inside] = chip
        colour[np.ix_(ys, xs)] = block
    return colour, height, rng.uniform(0.08, 0.3) + 0.1 * t


def pattern_weave(rng, size):
    u, v = coords(size)
    threads = int(rng.choice([32, 48, 64, 96]))
    warp = np.sin(math.pi * (u * threads % 1.0))
    weft = np.sin(math.pi * (v * threads % 1.0))
    over = (np.floor(u * threads) + np.floor(v * threads)) % 2 == 0
    height = np.where(over, warp, weft) * (0.85 + 0.15 * noise(rng, size, 64, 64, 2))
    a = hsv(rng.random(), rng.uniform(0.15, 0.8), rng.uniform(0.25, 0.85))
    b = a * rng.uniform(0.6, 0.95)
    colour = np.where(over[..., None], a, b) * (0.75 + 0.25 * height)[..., None]
    return colour, height, 0.75 + 0.2 * (1 - height)


def pattern_plaid(rng, size):
    u, v = coords(size)
    palette = [hsv(rng.random(), rng.uniform(0.3, 0.9), rng.uniform(0.2, 0.85)) for _ in range(3)]
    bands = int(rng.integers(2, 6))
    a = np.floor(u * bands * 2).astype(int) % 3
    b = np.floor(v * bands * 2).astype(int) % 3
    colour = 0.5 * (np.stack(palette)[a] + np.stack(palette)[b])
    fine = 0.5 + 0.5 * np.sin(2 * math.pi * 64 * (u + v))
    return colour * (0.85 + 0.15 * fine)[..., None], fine, 0.8 + 0.1 * fine


def pattern_leather(rng, size):
    creases = 1 - np.abs(2 * noise(rng, size, 24, 24, 4) - 1)
    base = hsv(rng.uniform(0.02, 0.1), rng.uniform(0.3, 0.8), rng.uniform(0.08, 0.6))
    colour = base * (0.7 + 0.3 * creases)[..., None]
    return colour, creases, 0.45 + 0.3 * (1 - creases)


def pattern_wallpaper(rng, size):
    u, v = coords(size)
    kind = rng.integers(0, 3)
    a = hsv(rng.random(), rng.uniform(0.05, 0.5), rng.uniform(0.55, 0.9))
    b = hsv(rng.random(), rng.uniform(0.05, 0.6), rng.uniform(0.3, 0.85))
    if kind == 0:  # stripes of random widths
        widths = rng.uniform(0.5, 2.0, int(rng.integers(3, 8)))
        edges = np.cumsum(widths) / widths.sum()
        t = (np.searchsorted(edges, u) % 2).astype(float)
    elif kind == 1:  # dots
        n = int(rng.integers(4, 12))
        r = rng.uniform(0.12, 0.35)
        t = (np.hypot(wrap_distance(u * n), wrap_distance(v * n)) < r).astype(float)
    else:  # diamonds
        n = int(rng.integers(3, 8))
        t = ((wrap_distance(u * n) + wrap_distance(v * n)) < 0.5).astype(float)
    plaster = noise(rng, size, 32, 32, 3)
    colour = (a * (1 - t)[..., None] + b * t[..., None]) * (0.93 + 0.07 * plaster)[..., None]
    return colour, 0.3 * t + 0.7 * plaster, 0.8 + 0.1 * plaster


def pattern_plaster(rng, size):
    plaster = noise(rng, size, 16, 16, 5)
    base = hsv(rng.random(), rng.uniform(0.02, 0.25), rng.uniform(0.6, 0.9))
    return base * (0.9 + 0.1 * plaster)[..., None], plaster, 0.85 + 0.1 * plaster


def pattern_brushed(rng, size):
    streaks = noise(rng, size, size // 2, 2, 2)
    base = hsv(rng.uniform(0.05, 0.6), rng.uniform(0.0, 0.4), rng.uniform(0.55, 0.95))
    colour = base * (0.9 + 0.1 * streaks)[..., None]
    return colour, streaks * 0.3, rng.uniform(0.2, 0.45) + 0.15 * streaks


def pattern_glaze(rng, size):
    u, v = coords(size)
    flow = noise(rng, size, 3, 3, 4)
    a = hsv(rng.random(), rng.uniform(0.2, 0.9), rng.uniform(0.3, 0.9))
    b = hsv(rng.random(), rng.uniform(0.2, 0.9), rng.uniform(0.2, 0.9))
    speck = (noise(rng, size, size // 4, size // 4, 1) > 0.93).astype(float)
    colour = a * flow[..., None] + b * (1 - flow)[..., None]
    colour *= (1 - 0.6 * speck)[..., None]
    if rng.random() < 0.4:  # painted bands
        band = (np.sin(2 * math.pi * v * rng.integers(2, 8)) > 0.6)[..., None]
        colour = np.where(band, hsv(rng.random(), 0.7, 0.5), colour)
    return colour, flow, 0.2 + 0.3 * speck


def pattern_book(rng, size):
    u, v = coords(size)
    base = hsv(rng.random(), rng.uniform(0.3, 0.9), rng.uniform(0.15, 0.8))
    band = hsv(rng.random(), rng.uniform(0.1, 0.9), rng.uniform(0.4, 0.95))
    bands = np.zeros_like(v, bool)
    for _ in range(int(rng.integers(1, 4))):
        c, w = rng.random(), rng.uniform(0.02, 0.1)
        bands |= wrap_distance(v - c) < w
    cloth = noise(rng, size, 64, 64, 2)
    colour = np.where(bands[..., None], band, base) * (0.9 + 0.1 * cloth)[..., None]
    return colour, cloth, 0.7 + 0.1 * cloth


def pattern_carpet(rng, size):
    u, v = coords(size)
    x, y = 2 * u - 1, 2 * v - 1
    palette = [hsv(rng.random(), rng.uniform(0.4, 0.9), rng.uniform(0.15, 0.7)) for _ in range(4)]
    border = np.maximum(np.abs(x), np.abs(y))
    ring = np.floor(np.hypot(x, y) * rng.integers(4, 9) + 0.5 * np.cos(rng.integers(4, 13) * np.arctan2(y, x)))
    index = np.where(border > 0.86, 0, np.where(border > 0.8, 1, 2 + ring.astype(int) % 2))
    pile = noise(rng, size, 128, 128, 2)
    colour = np.stack(palette)[index] * (0.8 + 0.2 * pile)[..., None]
    return colour, pile, 0.9 + 0.05 * pile


def pattern_painting(rng, size):
    u, v = coords(size)
    if rng.random() < 0.35:  # rectangles and black lines
        colour = np.ones((size, size, 3)) * hsv(0.1, 0.05, 0.92)
        for _ in range(int(rng.integers(3, 9))):
            x0, y0 = rng.random(2) * 0.8
            w, h = rng.uniform(0.1, 0.5, 2)
            sel = (u > x0) & (u < x0 + w) & (v > y0) & (v < y0 + h)
            colour[sel] = hsv(rng.choice([0.0, 0.15, 0.6, rng.random()]), rng.uniform(0.6, 1), rng.uniform(0.5, 0.9))
        for _ in range(int(rng.integers(2, 6))):
            c = rng.random()
            line = wrap_distance((u if rng.random() < 0.5 else v) - c) < 0.008
            colour[line] = 0.02
    else:  # soft colour fields
        colour = np.zeros((size, size, 3)) + hsv(rng.random(), rng.uniform(0.1, 0.6), rng.uniform(0.2, 0.9))
        for _ in range(int(rng.integers(4, 14))):
            cx, cy, r = rng.random(), rng.random(), rng.uniform(0.05, 0.35)
            weight = np.exp(-((u - cx) ** 2 + (v - cy) ** 2) / (2 * r * r))[..., None]
            colour = colour * (1 - weight) + hsv(rng.random(), rng.uniform(0.3, 1), rng.uniform(0.3, 1)) * weight
        colour *= (0.9 + 0.1 * noise(rng, size, 96, 96, 2))[..., None]
    return colour, np.zeros((size, size)), np.full((size, size), 0.6)


PATTERNS = {
    "floor": [pattern_planks, pattern_tiles, pattern_marble, lambda r, s: pattern_marble(r, s, 250)],
    "wall": [pattern_wallpaper, pattern_wallpaper, pattern_plaster, lambda r, s: pattern_tiles(r, s, bricks=True)],
    "rug": [pattern_carpet],
    "art": [pattern_painting],
    "wood": [lambda r, s: pattern_planks(r, s, planks=1)],
    "fabric": [pattern_weave, pattern_plaid, pattern_leather],
    "stone": [pattern_marble, lambda r, s: pattern_marble(r, s, 120)],
    "metal": [pattern_brushed],
    "ceramic": [pattern_glaze],
    "paper": [pattern_book],
}


def normal_map(height, strength):
    """Tangent-space normals (+x along u, +y along v up, OpenGL convention as glTF) as RGB."""
    dh_du = (np.roll(height, -1, axis=1) - np.roll(height, 1, axis=1)) * 0.5 * strength
    dh_dv = -(np.roll(height, -1, axis=0) - np.roll(height, 1, axis=0)) * 0.5 * strength  # rows run down
    n = np.stack([-dh_du, -dh_dv, np.ones_like(height)], axis=-1)
    return 0.5 + 0.5 * n / np.linalg.norm(n, axis=-1, keepdims=True)


def write_image(name, rgb, folder, jpeg, non_colour):
    """Writes rgb (rows top to bottom) through Blender as JPEG or PNG and returns the loaded image."""
    size = rgb.shape[0]
    image = bpy.data.images.new(name, size, size, alpha=False, is_data=non_colour)
    rgba = np.concatenate([np.clip(rgb, 0, 1), np.ones((size, size, 1))], axis=-1)[::-1]  # Blender: bottom row first
    image.pixels.foreach_set(rgba.astype(np.float32).ravel())
    image.filepath_raw = os.path.join(folder, name + (".jpg" if jpeg else ".png"))
    image.file_format = "JPEG" if jpeg else "PNG"
    image.save(quality=90) if jpeg else image.save()
    return image


# ---------------------------------------------------------------------------------------
# Materials. Parts ask for a category while the scene is built (a placeholder material);
# once every request is known, each category gets its materials and textures.

def principled(name, colour, roughness, metallic=0.0):
    mat = bpy.data.materials.new(name)
    mat.use_nodes = True
    node = mat.node_tree.nodes["Principled BSDF"]
    node.inputs["Base Color"].default_value = (*colour, 1.0)
    node.inputs["Metallic"].default_value = metallic
    node.inputs["Roughness"].default_value = roughness
    return mat


def textured(name, category, images):
    metal = category == "metal"
    mat = principled(name, (1.0, 1.0, 1.0), 0.5 if category in ("stone", "ceramic") else 0.8, 1.0 if metal else 0.0)
    tree = mat.node_tree
    node = tree.nodes["Principled BSDF"]
    tex = tree.nodes.new("ShaderNodeTexImage")
    tex.image = images["colour"]
    tree.links.new(tex.outputs["Color"], node.inputs["Base Color"])
    if "normal" in images:
        tex = tree.nodes.new("ShaderNodeTexImage")
        tex.image = images["normal"]
        normal = tree.nodes.new("ShaderNodeNormalMap")
        tree.links.new(tex.outputs["Color"], normal.inputs["Color"])
        tree.links.new(normal.outputs["Normal"], node.inputs["Normal"])
    if "rough" in images:  # glTF metallicRoughness: G roughness, B metallic
        tex = tree.nodes.new("ShaderNodeTexImage")
        tex.image = images["rough"]
        separate = tree.nodes.new("ShaderNodeSeparateColor")
        tree.links.new(tex.outputs["Color"], separate.inputs["Color"])
        tree.links.new(separate.outputs["Green"], node.inputs["Roughness"])
        if metal:
            tree.links.new(separate.outputs["Blue"], node.inputs["Metallic"])
    return mat


def allocate(requests, total):
    """Materials per category so that their images add up to exactly `total`: one for every
    category asked for, then the fixed categories one per request, then the others in
    proportion to their requests."""
    cost = {c: len(CATEGORIES[c][0]) for c in requests}
    count = {c: 1 for c in requests}
    left = total - sum(cost.values())
    if left < 0:
        sys.exit(f"make_big_room.py: --textures {total} is too few: one material of every category takes "
                 f"{sum(cost.values())} images")
    for c in FIXED:
        if c in requests:
            take = min(requests[c] - 1, left // cost[c])
            count[c], left = count[c] + take, left - take * cost[c]
    others = [c for c in requests if c not in FIXED]
    while left > 0:
        open_ = [c for c in others if count[c] < requests[c] and cost[c] <= left]
        if not open_:
            break
        c = min(open_, key=lambda c: (count[c] / requests[c], -cost[c], c))
        count[c] += 1
        left -= cost[c]
    if left:
        sys.exit(f"make_big_room.py: the scene has room for {total - left} distinct textures, not {total}: "
                 "lower --textures or raise --triangles")
    return count


# ---------------------------------------------------------------------------------------
# The builder: objects, placements, decoration slots, wall space.

class Place:
    """Where a piece stands: plan position and turn about z; local -y is the piece's front."""

    def __init__(self, x, y, degrees=0.0, z=0.0):
        self.x, self.y, self.z, self.degrees = x, y, z, degrees

    def world(self, p):
        c, s = math.cos(math.radians(self.degrees)), math.sin(math.radians(self.degrees))
        return (self.x + c * p[0] - s * p[1], self.y + s * p[0] + c * p[1], self.z + p[2])


class Builder:
    def __init__(self, seed):
        self.rng = np.random.default_rng(seed)
        self.scene = bpy.context.scene
        self.requests = []      # placeholder materials, in request order
        self.plain = {}
        self.modifiers = {}     # mesh name -> (bevel width, bevel segments, subdivision levels)
        self.designs = {}       # key -> mesh, for linked duplicates
        self.slots = []         # decoration slots: (x, y, z, radius, height, floor)
        self.occupied = {}      # (room, side) -> [(lo, hi)] of wall hidden by tall furniture
        self.names = {}

    def unique(self, name):
        n = self.names.get(name, 0)
        self.names[name] = n + 1
        return name if n == 0 else f"{name}_{n}"

    def material(self, category):
        if category.startswith("plain:"):
            key = category[6:]
            if key not in self.plain:
                colour, rough, metal = PLAIN[key]
                self.plain[key] = principled(f"plain_{key}", colour, rough, metal)
            return self.plain[key]
        mat = bpy.data.materials.new(f"request:{category}:{len(self.requests)}")
        self.requests.append(mat)
        return mat

    def mesh(self, name, parts, categories, bevel=None, subsurf=0, design=None):
        """A mesh from parts with one material slot per category; with `design`, made once and
        shared (linked duplicates)."""
        if design is not None and design in self.designs:
            return self.designs[design]
        verts, faces, slots = [], [], []
        for v, f, slot in parts:
            offset = len(verts)
            verts += v
            faces += [tuple(i + offset for i in face) for face in f]
            slots += [slot] * len(f)
        mesh = bpy.data.meshes.new(self.unique(name))
        mesh.from_pydata(verts, [], faces)
        mesh.polygons.foreach_set("material_index", slots)
        mesh.update()
        box_uvs(mesh, [None if c.startswith("plain:") else CATEGORIES[c][2] for c in categories])
        for c in categories:
            mesh.materials.append(self.material(c))
        smooth(mesh)
        if bevel or subsurf:
            self.modifiers[mesh.name] = (bevel, subsurf)
        if design is not None:
            self.designs[design] = mesh
        return mesh

    def place(self, name, mesh, place):
        obj = bpy.data.objects.new(self.unique(name), mesh)
        obj.location = (place.x, place.y, place.z)
        obj.rotation_euler = Euler((0.0, 0.0, math.radians(place.degrees)))
        self.scene.collection.objects.link(obj)
        spec = self.modifiers.get(mesh.name)
        if spec:
            (bevel, subsurf) = spec
            if bevel:
                mod = obj.modifiers.new("bevel", "BEVEL")
                mod.width, mod.segments = bevel[0], bevel[1]
                mod.limit_method = "ANGLE"
                mod.harden_normals = False
            if subsurf:
                mod = obj.modifiers.new("subsurf", "SUBSURF")
                mod.levels = mod.render_levels = subsurf
        return obj

    def slot(self, place, local, radius, height, floor=False):
        self.slots.append((*place.world(local), radius, height, floor))

    def occupy(self, room, side, lo, hi):
        self.occupied.setdefault((room, side), []).append((lo, hi))

    def bake(self):
        """Applies the modifiers once per mesh; the objects sharing a mesh keep sharing it."""
        depsgraph = bpy.context.evaluated_depsgraph_get()
        users = {}
        for obj in self.scene.objects:
            if obj.type == "MESH" and obj.modifiers:
                users.setdefault(obj.data.name, []).append(obj)
        for name, objs in users.items():
            old = objs[0].data
            new = bpy.data.meshes.new_from_object(objs[0].evaluated_get(depsgraph), preserve_all_data_layers=True,
                                                  depsgraph=depsgraph)
            for obj in objs:
                obj.modifiers.clear()
                obj.data = new
            for key, mesh in self.designs.items():
                if mesh == old:
                    self.designs[key] = new
            bpy.data.meshes.remove(old)
            new.name = name
            smooth(new)
        self.modifiers.clear()

    def triangles(self):
        per_mesh = {}
        total = 0
        for obj in self.scene.objects:
            if obj.type == "MESH":
                if obj.data.name not in per_mesh:
                    per_mesh[obj.data.name] = triangles_of(obj.data)
                total += per_mesh[obj.data.name]
        return total, sum(per_mesh.values())


def against(room, side, along, depth, gap=0.02):
    """A piece `depth` deep standing with its back to the wall `side` (N, S, W, E) of `room`."""
    x0, x1, y0, y1 = ROOMS[room]
    half = depth / 2 + gap
    return {"N": Place(along, y1 - half, 0.0), "S": Place(along, y0 + half, 180.0),
            "W": Place(x0 + half, along, 90.0), "E": Place(x1 - half, along, -90.0)}[side]


# ---------------------------------------------------------------------------------------
# Shell: floors, ceiling, walls with openings, sills.

def build_shell(b):
    floors = {"living": (-EXT, 9.0), "dining": (9.0, WIDTH + EXT), "bedroom": (-EXT, 7.0), "study": (7.0, WIDTH + EXT)}
    for room, (fx0, fx1) in floors.items():
        _, _, y0, y1 = ROOMS[room]
        fy0 = -EXT if y0 == 0.0 else 6.5
        fy1 = 6.5 if y0 == 0.0 else DEPTH + EXT
        b.place(f"floor_{room}", b.mesh(f"floor_{room}", [box(fx0, fx1, fy0, fy1, -0.1, 0.0)], ["floor"]), Place(0, 0))
    ceiling = b.mesh("ceiling", [box(-EXT, WIDTH + EXT, -EXT, DEPTH + EXT, HEIGHT, HEIGHT + 0.12)], ["plain:ceiling"])
    b.place("ceiling", ceiling, Place(0, 0))
    for name, axis, line, (a0, a1), (t0, t1), openings in WALLS:
        parts, cuts = [], [a0]
        for lo, hi, z0, z1 in sorted(openings):
            cuts += [lo, hi]
        cuts.append(a1)
        for lo, hi in zip(cuts[0::2], cuts[1::2]):
            parts.append((lo, hi, 0.0, HEIGHT))
        for lo, hi, z0, z1 in openings:
            if z0 > 0:
                parts.append((lo, hi, 0.0, z0))
            parts.append((lo, hi, z1, HEIGHT))
        boxes = [box(lo, hi, t0, t1, z0, z1) if axis == "x" else box(t0, t1, lo, hi, z0, z1)
                 for lo, hi, z0, z1 in parts]
        b.place(name, b.mesh(name, boxes, ["wall"]), Place(0, 0))
        for lo, hi, z0, z1 in openings:
            if z0 <= 0:
                continue
            inward = 1.0 if line < 1.0 else -1.0  # exterior walls only carry windows
            face = t1 if inward > 0 else t0
            sill_t = (face - 0.02, face + 0.2) if inward > 0 else (face - 0.2, face + 0.02)
            sill = (box(lo - 0.05, hi + 0.05, *sill_t, z0 - 0.04, z0 + 0.01) if axis == "x"
                    else box(*sill_t, lo - 0.05, hi + 0.05, z0 - 0.04, z0 + 0.01))
            b.place(f"sill_{name}", b.mesh("sill", [sill], ["stone"], bevel=(0.006, 2)), Place(0, 0))
            mid = face + inward * 0.1
            for k in range(2):
                along = lo + (hi - lo) * (0.25 + 0.5 * k)
                b.slot(Place(along, mid) if axis == "x" else Place(mid, along), (0, 0, z0 + 0.01), 0.08, 0.35)


def openings_on(room, side):
    """Wall openings (lo, hi, z0, z1) along the room's side."""
    x0, x1, y0, y1 = ROOMS[room]
    axis, line = {"N": ("x", y1), "S": ("x", y0), "W": ("y", x0), "E": ("y", x1)}[side]
    found = []
    for _, wall_axis, wall_line, _, _, openings in WALLS:
        if wall_axis == axis and abs(wall_line - line) < 0.1:
            found += openings
    return found


# ---------------------------------------------------------------------------------------
# Furniture. Each design is modelled about its own origin, front towards -y, and placed.

def table(b, name, place, w, d, h, top="wood", legs="wood", slots=1):
    mesh = b.mesh(name, [cbox(0, 0, w, d, h - 0.04, h, 0)] +
                  [cylinder((sx * (w / 2 - 0.08), sy * (d / 2 - 0.08), 0), (sx * (w / 2 - 0.08), sy * (d / 2 - 0.08), h - 0.04),
                            0.025, 16, 1) for sx in (-1, 1) for sy in (-1, 1)],
                  [top, legs], bevel=(0.008, 3), design=(name, w, d, h))
    b.place(name, mesh, place)
    for k in range(slots):
        b.slot(place, ((k + 0.5) / slots * w * 0.8 - 0.4 * w, 0.15 * d * (-1) ** k, h), min(0.12, d / 4), 0.45)


def chair(b, place, style):
    if style == "a":  # wooden chair with a seat cushion
        parts = [cbox(0, 0, 0.44, 0.44, 0.42, 0.46, 0), cbox(0, -0.01, 0.40, 0.38, 0.46, 0.51, 1)]
        parts += [cbox(sx * 0.19, sy * 0.19, 0.035, 0.035, 0.0, 0.42, 0) for sx in (-1, 1) for sy in (-1, 1)]
        parts += [cbox(sx * 0.19, 0.2, 0.035, 0.035, 0.46, 0.95, 0) for sx in (-1, 1)]
        parts += [cbox(0, 0.2, 0.36, 0.02, z, z + 0.07, 0) for z in (0.6, 0.72, 0.84)]
        mesh = b.mesh("chair_a", parts, ["wood", "fabric"], bevel=(0.006, 2), subsurf=1, design="chair_a")
    else:  # moulded shell on tube legs
        parts = [tilted(cbox(0, 0, 0.46, 0.46, 0.43, 0.46, 0), -4, (0, 0.43))]
        parts.append(tilted(cbox(0, 0.23, 0.44, 0.03, 0.46, 0.86, 0), 10, (0.23, 0.46)))
        parts += [cylinder((sx * 0.2, sy * 0.2, 0), (sx * 0.17, sy * 0.17, 0.43), 0.012, 10, 1)
                  for sx in (-1, 1) for sy in (-1, 1)]
        mesh = b.mesh("chair_b", parts, ["wood", "metal"], bevel=(0.01, 2), subsurf=1, design="chair_b")
    b.place(f"chair_{style}", mesh, place)


def stool(b, place):
    parts = [lathe_part([(0.18, 0.72), (0.19, 0.75), (0.17, 0.78)], 24, 0, cap_top=True)]
    feet = [(0.2 * math.cos(a), 0.2 * math.sin(a)) for a in np.radians([45, 135, 225, 315])]
    tops = [(0.12 * math.cos(a), 0.12 * math.sin(a)) for a in np.radians([45, 135, 225, 315])]
    parts += [cylinder((fx, fy, 0), (tx, ty, 0.72), 0.014, 10, 1) for (fx, fy), (tx, ty) in zip(feet, tops)]
    ring = [(0.175 * math.cos(a), 0.175 * math.sin(a), 0.28) for a in np.radians([45, 135, 225, 315])]
    parts += [cylinder(ring[k], ring[(k + 1) % 4], 0.01, 8, 1) for k in range(4)]
    b.place("stool", b.mesh("stool", parts, ["wood", "metal"], bevel=(0.004, 2), design="stool"), place)


def office_chair(b, place):
    soft = b.mesh("office_chair_seat", [cbox(0, 0, 0.48, 0.46, 0.45, 0.53), tilted(cbox(0, 0.24, 0.45, 0.07, 0.58, 1.1), 8, (0.24, 0.58))],
                  ["fabric"], bevel=(0.03, 2), subsurf=2, design="office_seat")
    base = [cylinder((0, 0, 0.1), (0, 0, 0.45), 0.025, 16, 0)]
    for k in range(5):
        a = 72 * k
        base.append(rotated(cbox(0.16, 0, 0.3, 0.04, 0.07, 0.1, 0), a))
        base.append(rotated(cylinder((0.3, -0.02, 0.03), (0.3, 0.02, 0.03), 0.03, 12, 1), a))
    hard = b.mesh("office_chair_base", base, ["metal", "plain:black"], bevel=(0.005, 2), design="office_base")
    b.place("office_chair_seat", soft, place)
    b.place("office_chair_base", hard, place)


def sofa(b, place, seats):
    w = 0.75 * seats + 0.4
    parts = [cbox(0, 0, w - 0.3, 0.85, 0.1, 0.4)]
    for k in range(seats):
        x = -w / 2 + 0.2 + 0.75 * (k + 0.5)
        parts.append(cbox(x, -0.08, 0.74, 0.68, 0.4, 0.56))
        parts.append(tilted(cbox(x, 0.3, 0.74, 0.2, 0.42, 0.88), 8, (0.3, 0.42)))
    parts += [cbox(sx * (w / 2 - 0.1), 0, 0.2, 0.9, 0.1, 0.64) for sx in (-1, 1)]
    soft = b.mesh(f"sofa_{seats}", parts, ["fabric"], bevel=(0.04, 2), subsurf=2, design=("sofa", seats))
    feet = b.mesh(f"sofa_feet_{seats}", [cylinder((sx * (w / 2 - 0.1), sy * 0.35, 0), (sx * (w / 2 - 0.1), sy * 0.35, 0.1), 0.025, 12)
                                         for sx in (-1, 1) for sy in (-1, 1)], ["wood"], bevel=(0.005, 2),
                  design=("sofa_feet", seats))
    b.place(f"sofa_{seats}", soft, place)
    b.place(f"sofa_feet_{seats}", feet, place)
    return w


def cabinet(b, name, place, w, h, d, doors, legs=True, design=None):
    """Sideboard, nightstand, wardrobe: body, door fronts, handles, feet."""
    z0 = 0.1 if legs else 0.0
    parts = [cbox(0, 0, w, d, z0, h, 0)]
    dw = (w - 0.02) / doors
    for k in range(doors):
        x = -w / 2 + 0.01 + dw * (k + 0.5)
        parts.append(cbox(x, -d / 2 - 0.008, dw - 0.006, 0.016, z0 + 0.02, h - 0.02, 0))
        hx = x + (dw / 2 - 0.05) * (1 if k % 2 == 0 else -1)
        hz = (z0 + h) / 2 + (0.3 if h > 1.5 else 0.0)
        parts.append(cylinder((hx, -d / 2 - 0.016, hz - 0.06), (hx, -d / 2 - 0.016, hz + 0.06), 0.008, 8, 1))
    if legs:
        parts += [cylinder((sx * (w / 2 - 0.05), sy * (d / 2 - 0.05), 0), (sx * (w / 2 - 0.05), sy * (d / 2 - 0.05), z0), 0.02, 12, 1)
                  for sx in (-1, 1) for sy in (-1, 1)]
    mesh = b.mesh(name, parts, ["wood", "metal"], bevel=(0.004, 2), design=design)
    b.place(name, mesh, place)


def bookshelf(b, room, side, along, w, h, depth=0.34):
    place = against(room, side, along, depth)
    boards = int(round(h / 0.38))
    spacing = (h - 0.05) / boards
    frame = [cbox(sx * (w / 2 - 0.012), 0, 0.024, depth, 0, h) for sx in (-1, 1)]
    frame.append(cbox(0, depth / 2 - 0.006, w, 0.012, 0, h))
    frame += [cbox(0, 0, w - 0.048, depth - 0.012, 0.03 + k * spacing, 0.05 + k * spacing) for k in range(boards + 1)]
    b.place("shelf", b.mesh("shelf", frame, ["wood"], bevel=(0.003, 1), design=("shelf", w, h)), place)
    for k in range(boards):  # each board's books one object; one or two gaps for decorations
        z = 0.05 + k * spacing
        gaps = [(float(b.rng.uniform(lo, hi)), float(b.rng.uniform(0.2, 0.28)))
                for lo, hi in ((-w / 2 + 0.05, -0.3), (0.02, w / 2 - 0.33)) if b.rng.random() < 0.8]
        books, x = [], -w / 2 + 0.03
        while x < w / 2 - 0.06:
            gap = next((g for g in gaps if g[0] <= x < g[0] + g[1]), None)
            if gap is not None:
                b.slot(place, (x + gap[1] / 2, 0.0, z), gap[1] / 2 - 0.02, spacing - 0.04)
                x += gap[1]
                continue
            t = float(b.rng.uniform(0.02, 0.05))
            if x + t > w / 2 - 0.03:
                break
            hb = float(b.rng.uniform(0.6, 0.85)) * (spacing - 0.02)
            db = float(b.rng.uniform(0.16, depth - 0.06))
            books.append(box(x, x + t, depth / 2 - 0.02 - db, depth / 2 - 0.02, z, z + hb, int(b.rng.integers(0, 3))))
            x += t + 0.003
        b.place("books", b.mesh("books", books, ["paper", "paper", "paper"]), place)
    b.slot(place, (0, 0, h), 0.12, 0.35)
    b.occupy(room, side, along - w / 2, along + w / 2)


def bed(b, place, w, length):
    frame = [cbox(0, 0, w + 0.08, length, 0.12, 0.32), cbox(0, length / 2 - 0.04, w + 0.12, 0.08, 0.0, 1.1)]
    frame += [cbox(sx * (w / 2), sy * (length / 2 - 0.1), 0.06, 0.06, 0, 0.12) for sx in (-1, 1) for sy in (-1, 1)]
    b.place("bed_frame", b.mesh("bed_frame", frame, ["wood"], bevel=(0.01, 2)), place)
    soft = [cbox(0, -0.02, w, length - 0.12, 0.32, 0.54, 0),
            cbox(0, -0.32, w + 0.06, length - 0.7, 0.5, 0.6, 1)]
    soft += [cbox(sx * w / 4, length / 2 - 0.35, w / 2 - 0.08, 0.38, 0.54, 0.68, 2) for sx in (-1, 1)]
    b.place("bed", b.mesh("bed", soft, ["plain:mattress", "fabric", "fabric"], bevel=(0.04, 2), subsurf=2), place)


def kitchen(b):
    room = "dining"
    x0, x1 = 12.4, 15.15
    place = against(room, "N", (x0 + x1) / 2, 0.62)
    w = x1 - x0
    cabinet(b, "kitchen_base", place, w, 0.87, 0.6, doors=int(round(w / 0.6)), legs=False)
    top = b.mesh("worktop", [cbox(0, -0.01, w + 0.02, 0.64, 0.87, 0.91)], ["stone"], bevel=(0.005, 2))
    b.place("worktop", top, place)
    sink = [cbox(-0.6, -0.02, 0.6, 0.42, 0.911, 0.915, 0), cylinder((-0.6, 0.15, 0.91), (-0.6, 0.15, 1.15), 0.012, 12, 0)]
    hob = [cbox(0.55, -0.02, 0.6, 0.5, 0.911, 0.916, 1)]
    b.place("sink_hob", b.mesh("sink_hob", sink + hob, ["metal", "plain:black"], bevel=(0.003, 1)), place)
    upper = Place(place.x, place.y + 0.13, 0, 1.45)
    cabinet(b, "kitchen_upper", upper, w, 0.7, 0.35, doors=int(round(w / 0.6)), legs=False)
    fridge = against(room, "N", 15.55, 0.66)
    cabinet(b, "fridge", fridge, 0.76, 1.95, 0.66, doors=1, legs=False)
    b.occupy(room, "N", x0, WIDTH)
    for k in range(3):
        b.slot(place, (-w / 2 + 0.3 + k * (w - 0.6) / 2 + 0.1, 0.05, 0.91), 0.1, 0.35)
    island = Place(14.2, 4.3)
    cabinet(b, "island", island, 1.8, 0.87, 0.9, doors=3, legs=False)
    b.place("island_top", b.mesh("island_top", [cbox(0, 0.1, 1.9, 1.15, 0.87, 0.91)], ["stone"], bevel=(0.005, 2)), island)
    for k in range(2):
        b.slot(island, (-0.5 + k, 0.2, 0.91), 0.12, 0.4)
    for x in (13.6, 14.2, 14.8):
        stool(b, Place(x, 3.45, 180))


def lamp(b, place, height, light_watts, floor_lamp):
    """A lamp: base, pole, open shade (fabric) and a point light inside the shade."""
    r = 0.22 if floor_lamp else 0.14
    shade_h = 0.3 if floor_lamp else 0.2
    foot = 0.15 if floor_lamp else 0.08
    base = [lathe_part([(foot, 0.0), (foot - 0.01, 0.03), (0.03, 0.035)], 32, 0, cap_top=True),
            cylinder((0, 0, 0.03), (0, 0, height - shade_h / 2), 0.012, 12, 0)]
    shade = lathe_part([(r, height - shade_h), (r * 0.7, height)], 48, 1, cap_bottom=False)
    mesh = b.mesh("floor_lamp" if floor_lamp else "table_lamp", base + [shade], ["metal", "fabric"], bevel=(0.003, 1),
                  design=("lamp", floor_lamp))
    b.place("lamp", mesh, place)
    add_light(f"lamp_light_{len(bpy.data.lights)}", "POINT", light_watts, place.world((0, 0, height - shade_h * 0.6)))


def rug(b, place, w, d):
    b.place("rug", b.mesh("rug", [cbox(0, 0, w, d, 0.0, 0.012)], ["rug"], bevel=(0.004, 1)), place)


def tv(b, place):
    cabinet(b, "tv_unit", place, 1.8, 0.5, 0.45, doors=3)
    screen = [cbox(0, 0.05, 1.25, 0.05, 0.62, 1.35, 0), cbox(0, 0.05, 0.3, 0.2, 0.5, 0.52, 1), cbox(0, 0.06, 0.05, 0.03, 0.5, 0.62, 1)]
    b.place("tv", b.mesh("tv", screen, ["plain:screen", "metal"], bevel=(0.004, 2)), place)


def painting(b, place, w, h):
    frame_w = 0.04
    parts = [cbox(0, -0.02, w, 0.04, -h / 2, -h / 2 + frame_w), cbox(0, -0.02, w, 0.04, h / 2 - frame_w, h / 2),
             cbox(-w / 2 + frame_w / 2, -0.02, frame_w, 0.04, -h / 2 + frame_w, h / 2 - frame_w),
             cbox(w / 2 - frame_w / 2, -0.02, frame_w, 0.04, -h / 2 + frame_w, h / 2 - frame_w)]
    canvas = cbox(0, -0.02, w - 2 * frame_w, 0.03, -h / 2 + frame_w, h / 2 - frame_w, 1)  # its front 5 mm behind the frame's
    frame_cat = "wood" if b.rng.random() < 0.6 else "metal"
    b.place("painting", b.mesh("painting", parts + [canvas], [frame_cat, "art"], bevel=(0.004, 1)), place)


def paintings(b):
    """Framed paintings on the wall space left by windows, doors and tall furniture."""
    for room, (x0, x1, y0, y1) in ROOMS.items():
        for side in "NSWE":
            lo, hi = (x0, x1) if side in "NS" else (y0, y1)
            blocked = [(o_lo, o_hi) for o_lo, o_hi, _, _ in openings_on(room, side)] + b.occupied.get((room, side), [])
            blocked = sorted((a - 0.25, c + 0.25) for a, c in blocked)
            free, at = [], lo + 0.3
            for a, c in blocked + [(hi - 0.3, hi)]:
                if a > at:
                    free.append((at, a))
                at = max(at, c)
            for a, c in free:
                x = a
                while True:
                    w = float(b.rng.uniform(0.45, 1.1))
                    if x + w > c:
                        break
                    h = float(b.rng.uniform(0.4, 0.8))
                    z = 1.65 + float(b.rng.uniform(-0.05, 0.1))
                    place = against(room, side, x + w / 2, 0.0, gap=0.0)
                    place.z = z
                    painting(b, place, w, h)
                    x += w + float(b.rng.uniform(0.3, 0.6))


# ---------------------------------------------------------------------------------------
# Rooms.

def living(b):
    room = "living"
    sofa(b, against(room, "N", 2.6, 0.9), 3)
    b.occupy(room, "N", 4.1, 4.7)  # the floor lamp's shade
    sofa(b, against(room, "W", 3.0, 0.9), 2)
    table(b, "coffee_table", Place(2.6, 3.3), 1.2, 0.6, 0.42, top="stone", legs="metal", slots=2)
    rug(b, Place(2.7, 3.4), 3.2, 2.4)
    sofa(b, Place(4.75, 2.5, -90), 1)
    sofa(b, Place(4.75, 4.2, -90), 1)
    table(b, "side_table", Place(0.55, 5.95), 0.5, 0.5, 0.55, slots=1)
    table(b, "side_table", Place(0.55, 1.3), 0.5, 0.5, 0.55, slots=1)
    lamp(b, Place(4.4, 5.95), 1.6, 25.0, True)
    lamp(b, Place(1.0, 0.45), 1.6, 25.0, True)
    b.occupy(room, "S", 0.7, 1.3)
    tv(b, against(room, "S", 4.5, 0.45))
    b.occupy(room, "S", 3.5, 5.5)
    for k, y in enumerate((4.95, 5.85)):
        bookshelf(b, room, "E", y, 0.85, 2.0)
    bookshelf(b, room, "E", 0.8, 0.9, 1.6)
    cabinet(b, "sideboard", against(room, "N", 7.6, 0.45), 2.0, 0.8, 0.45, doors=4)
    b.slot(against(room, "N", 7.6, 0.45), (-0.5, 0, 0.8), 0.15, 0.5)
    b.slot(against(room, "N", 7.6, 0.45), (0.5, 0, 0.8), 0.15, 0.5)
    for x, y in ((0.35, 0.35), (7.9, 0.4), (6.3, 6.1)):
        b.slot(Place(x, y), (0, 0, 0), 0.3, 1.3, floor=True)


def dining(b):
    room = "dining"
    table(b, "dining_table", Place(11.4, 2.8), 2.0, 1.0, 0.75, slots=3)
    for x in (10.75, 11.4, 12.05):
        chair(b, Place(x, 2.05, 180), "a")
        chair(b, Place(x, 3.55, 0), "a")
    chair(b, Place(9.95, 2.8, 90), "a")
    chair(b, Place(12.85, 2.8, -90), "a")
    kitchen(b)
    cabinet(b, "sideboard", against(room, "E", 1.0, 0.45), 1.4, 0.8, 0.45, doors=2)
    b.slot(against(room, "E", 1.0, 0.45), (0.0, 0, 0.8), 0.15, 0.5)
    cabinet(b, "sideboard", against(room, "S", 14.7, 0.45), 2.0, 0.8, 0.45, doors=4)
    for dx in (-0.6, 0.6):
        b.slot(against(room, "S", 14.7, 0.45), (dx, 0, 0.8), 0.15, 0.5)
    for x, y in ((9.45, 0.4), (15.6, 5.2), (9.5, 6.0)):
        b.slot(Place(x, y), (0, 0, 0), 0.3, 1.3, floor=True)


def bedroom(b):
    room = "bedroom"
    bed(b, against(room, "W", 8.8, 2.1, gap=0.0), 1.6, 2.1)
    for y in (7.65, 9.95):
        place = against(room, "W", y, 0.42)
        cabinet(b, "nightstand", place, 0.45, 0.55, 0.42, doors=1, design="nightstand")
        lamp(b, Place(place.x, place.y, 0, 0.55), 0.5, 12.0, False)
        b.slot(place, (0.12, 0.05, 0.55), 0.06, 0.25)
    b.occupy(room, "W", 7.3, 10.3)
    cabinet(b, "wardrobe", against(room, "S", 1.45, 0.6), 2.4, 2.1, 0.6, doors=4, legs=False)
    b.occupy(room, "S", 0.2, 2.7)
    cabinet(b, "dresser", against(room, "N", 2.4, 0.45), 1.8, 0.8, 0.45, doors=3)
    b.slot(against(room, "N", 2.4, 0.45), (-0.5, 0, 0.8), 0.15, 0.5)
    b.slot(against(room, "N", 2.4, 0.45), (0.5, 0, 0.8), 0.15, 0.5)
    sofa(b, Place(5.4, 10.1, 160), 1)
    rug(b, Place(1.9, 8.8), 3.0, 2.4)
    for y in (9.3, 10.15):
        bookshelf(b, room, "E", y, 0.8, 1.6)
    for x, y in ((6.55, 6.95), (0.35, 10.65), (3.9, 7.0)):
        b.slot(Place(x, y), (0, 0, 0), 0.3, 1.3, floor=True)


def study(b):
    room = "study"
    for x in (11.25, 14.25):
        place = against(room, "N", x, 0.7)
        desk = [cbox(0, 0, 1.4, 0.7, 0.72, 0.75, 0), cbox(0.45, 0, 0.42, 0.6, 0.0, 0.72, 0)]
        desk += [cylinder((-0.64, sy * 0.28, 0), (-0.64, sy * 0.28, 0.72), 0.02, 12, 1) for sy in (-1, 1)]
        b.place("desk", b.mesh("desk", desk, ["wood", "metal"], bevel=(0.005, 2), design="desk"), place)
        b.slot(place, (-0.45, 0.15, 0.75), 0.12, 0.45)
        office_chair(b, Place(x - 0.1, 9.85, 180))
    for k, x in enumerate((7.55, 8.45, 9.35, 10.25, 12.75, 13.65, 14.55, 15.45)):
        bookshelf(b, room, "S", x, 0.88, 2.0 if k % 2 == 0 else 1.6)
    sofa(b, against(room, "W", 9.8, 0.9), 2)
    table(b, "coffee_table", Place(8.6, 9.8, 90), 1.2, 0.6, 0.42, top="stone", legs="metal", slots=2)
    rug(b, Place(8.4, 9.8), 2.4, 2.2)
    lamp(b, Place(7.4, 8.7), 1.6, 25.0, True)
    b.occupy(room, "W", 8.4, 9.0)
    table(b, "meeting_table", Place(12.8, 8.4), 1.6, 0.9, 0.75, top="stone", legs="metal", slots=2)
    for x in (12.4, 13.2):
        chair(b, Place(x, 7.7, 180), "b")
        chair(b, Place(x, 9.1, 0), "b")
    for x, y in ((15.6, 7.0), (15.6, 10.6), (10.7, 7.2)):
        b.slot(Place(x, y), (0, 0, 0), 0.3, 1.3, floor=True)


# ---------------------------------------------------------------------------------------
# Decoration: triangle-budgeted vases, bowls, sculptures and plants.

def lathe_arrays(radii, heights, segments):
    """Vertices and quads of a surface of revolution, plus its bottom cap as one n-gon."""
    a = 2 * np.pi * np.arange(segments) / segments
    verts = np.stack([np.outer(radii, np.cos(a)), np.outer(radii, np.sin(a)), np.repeat(heights[:, None], segments, 1)], -1)
    rows = len(radii)
    i = np.arange(segments)
    quads = np.concatenate([np.stack([k * segments + i, k * segments + (i + 1) % segments,
                                      (k + 1) * segments + (i + 1) % segments, (k + 1) * segments + i], 1)
                            for k in range(rows - 1)])
    return verts.reshape(-1, 3), [quads, i[::-1][None, :]]


def decor_vase(rng, radius, height, budget):
    """A vase or bowl (open top, capped bottom): 2 x segments x (rows - 1) + segments - 2 triangles."""
    segments = int(np.clip(round(math.sqrt(budget / 3)), 12, 720))
    rows = max(3, int(round((budget - segments + 2) / (2 * segments))) + 1)
    t = np.linspace(0, 1, rows)
    bowl = rng.random() < 0.3
    h = height * (rng.uniform(0.25, 0.4) if bowl else rng.uniform(0.55, 1.0))
    shape = 0.55 + 0.35 * np.sin(np.pi * t * rng.uniform(0.6, 1.4) + rng.uniform(0, 1)) + 0.1 * np.sin(2 * np.pi * t * rng.integers(2, 6))
    r = radius * np.clip(shape, 0.15, 1.0) * (np.sqrt(t) if bowl else 1.0)
    r[0] = max(r[0], radius * 0.3)
    return lathe_arrays(r, h * t, segments), "ceramic"


def decor_blob(rng, radius, height, budget):
    """A sculpture: a sphere displaced by a few sine waves, 2 x segments x rings triangles."""
    segments = int(np.clip(round(math.sqrt(budget)), 12, 1024))
    rings = max(3, int(round(budget / (2 * segments))))
    theta = np.linspace(0, np.pi, rings + 1)[1:-1]
    phi = 2 * np.pi * np.arange(segments) / segments
    T, P = np.meshgrid(theta, phi, indexing="ij")
    bump = 1 + 0.15 * np.sin(rng.integers(2, 7) * P + rng.uniform(0, 6)) * np.sin(rng.integers(1, 5) * T) \
        + 0.08 * np.sin(rng.integers(3, 11) * T + rng.integers(1, 6) * P)
    r = min(radius, height / 2) * 0.85 / 1.23
    verts = np.stack([r * bump * np.sin(T) * np.cos(P), r * bump * np.sin(T) * np.sin(P), r * 1.23 + r * bump * np.cos(T)], -1)
    verts = verts.reshape(-1, 3)
    verts = np.concatenate([verts, [[0, 0, r * 1.23 + r], [0, 0, r * 1.23 - r]]])
    top, bottom = len(verts) - 2, len(verts) - 1
    i = np.arange(segments)
    quads = [np.stack([(k + 1) * segments + i, (k + 1) * segments + (i + 1) % segments,
                       k * segments + (i + 1) % segments, k * segments + i], 1) for k in range(rings - 2)]
    last = (rings - 2) * segments
    tris = np.concatenate([np.stack([np.full(segments, top), i, (i + 1) % segments], 1),
                           np.stack([np.full(segments, bottom), last + (i + 1) % segments, last + i], 1)])
    return (verts, [np.concatenate(quads), tris]), ("stone" if rng.random() < 0.6 else "metal")


def decor_knot(rng, radius, height, budget):
    """A (p, q) torus-knot tube: 2 x path x ring triangles."""
    ring = int(np.clip(round(math.sqrt(budget / 24)), 6, 64))
    path = max(24, int(round(budget / (2 * ring))))
    p, q = [(2, 3), (3, 4), (2, 5), (3, 5)][int(rng.integers(0, 4))]
    t = 2 * np.pi * np.arange(path) / path
    size = min(radius, height / 2) * 0.6
    centre = np.stack([(2 + np.cos(q * t)) * np.cos(p * t), (2 + np.cos(q * t)) * np.sin(p * t), np.sin(q * t)], 1) * size / 3
    tangent = np.roll(centre, -1, 0) - np.roll(centre, 1, 0)
    tangent /= np.linalg.norm(tangent, axis=1, keepdims=True)
    normal = np.cross(tangent, [0.0, 0.0, 1.0])
    normal /= np.linalg.norm(normal, axis=1, keepdims=True) + 1e-9
    binormal = np.cross(tangent, normal)
    a = 2 * np.pi * np.arange(ring) / ring
    tube = size * 0.12
    verts = centre[:, None, :] + tube * (np.cos(a)[None, :, None] * normal[:, None, :] + np.sin(a)[None, :, None] * binormal[:, None, :])
    verts = verts.reshape(-1, 3) + [0, 0, size * 0.5]
    k, j = np.meshgrid(np.arange(path), np.arange(ring), indexing="ij")
    k, j = k.ravel(), j.ravel()
    quads = np.stack([k * ring + j, k * ring + (j + 1) % ring, ((k + 1) % path) * ring + (j + 1) % ring, ((k + 1) % path) * ring + j], 1)
    return (verts, [quads]), "metal"


PLANT_POT_BUDGET = 600
PLANT_POT_SEGMENTS = int(np.clip(round(math.sqrt(PLANT_POT_BUDGET / 3)), 12, 720))
PLANT_POT_QUADS = PLANT_POT_SEGMENTS * (max(3, int(round((PLANT_POT_BUDGET - PLANT_POT_SEGMENTS + 2) / (2 * PLANT_POT_SEGMENTS))) + 1) - 1)


def decor_plant(rng, radius, height, budget):
    """A potted plant: the pot (a vase) and bent leaves, 2 x (length - 1) x (width - 1) triangles each."""
    (pot_v, pot_p), _ = decor_vase(rng, radius * 0.55, height * 0.35, PLANT_POT_BUDGET)
    pot_h = pot_v[:, 2].max()
    length, width = 11, 5
    per_leaf = 2 * (length - 1) * (width - 1)
    leaves = max(6, int(round((budget - PLANT_POT_BUDGET) / per_leaf)))
    assert len(pot_p[0]) == PLANT_POT_QUADS
    verts, quads = [pot_v], [pot_p[0]]
    caps = [pot_p[1]]
    offset = len(pot_v)
    s = np.linspace(0, 1, length)[:, None]
    w = np.linspace(-1, 1, width)[None, :]
    for _ in range(leaves):
        ang = rng.uniform(0, 2 * np.pi)
        leaf_len = rng.uniform(0.5, 0.9) * (height - pot_h)
        tilt = rng.uniform(0.2, max(0.25, min(1.2, math.asin(min(1.0, 0.8 * radius / leaf_len)))))  # within the slot
        half_w = leaf_len * rng.uniform(0.08, 0.16) * np.sin(np.pi * s) + 0.002
        along = leaf_len * s * np.sin(tilt)
        up = leaf_len * s * np.cos(tilt) - 0.5 * (s ** 2) * leaf_len * np.sin(tilt) * 0.6
        x = along * np.cos(ang) - w * half_w * np.sin(ang)
        y = along * np.sin(ang) + w * half_w * np.cos(ang)
        z = pot_h * 0.9 + up + 0 * w + 0.02 * np.abs(w)
        verts.append(np.stack([x, y, z], -1).reshape(-1, 3))
        a, c = np.meshgrid(np.arange(length - 1), np.arange(width - 1), indexing="ij")
        a, c = a.ravel(), c.ravel()
        quads.append(offset + np.stack([a * width + c, a * width + c + 1, (a + 1) * width + c + 1, (a + 1) * width + c], 1))
        offset += length * width
    return (np.concatenate(verts), [np.concatenate(quads)] + caps), "ceramic"


def build_decor(b, target, furniture_triangles):
    """Fills the decoration slots so that the scene reaches `target` triangles."""
    rng = b.rng
    slots = [b.slots[i] for i in rng.permutation(len(b.slots))]
    weights = np.array([(2.5 if s[5] else 1.0) * rng.uniform(0.6, 1.4) for s in slots])
    remaining = target - furniture_triangles
    made = []  # (mesh, radius, height, triangles) for linked duplicates
    for k, (x, y, z, radius, height, floor) in enumerate(slots):
        share = weights[k] / weights[k:].sum()
        budget = remaining * share
        last = k == len(slots) - 1
        fits = [m for m in made if m[1] <= radius * 1.05 and m[2] <= height * 1.05 and m[3] <= budget * 1.5]
        if not last and fits and rng.random() < 0.18:
            mesh, _, _, tris = fits[int(rng.integers(0, len(fits)))]
        else:
            budget = max(200, budget)
            kind = (decor_plant if floor and rng.random() < 0.6 else
                    [decor_vase, decor_vase, decor_blob, decor_knot][int(rng.integers(0, 4))])
            (verts, polys), category = kind(rng, radius, height, budget)
            mesh = mesh_from_arrays(b.unique(kind.__name__), verts, polys)
            categories = [category]
            if kind is decor_plant:  # pot quads, leaf quads, pot cap: the leaves get the second slot
                categories.append("plain:leaf")
                slots_of = np.zeros(len(mesh.polygons), np.int32)
                slots_of[PLANT_POT_QUADS:len(polys[0])] = 1
                mesh.polygons.foreach_set("material_index", slots_of)
            mesh.update()
            box_uvs(mesh, [None if c.startswith("plain:") else CATEGORIES[c][2] for c in categories])
            for c in categories:
                mesh.materials.append(b.material(c))
            smooth(mesh, 60.0)
            tris = triangles_of(mesh)
            extent = np.asarray(verts)
            made.append((mesh, float(np.abs(extent[:, :2]).max()), float(extent[:, 2].max()), tris))
        b.place(mesh.name.split("_")[0], mesh, Place(x, y, float(rng.uniform(0, 360)), z))
        remaining -= tris


# ---------------------------------------------------------------------------------------
# Lights, camera.

def look_rotation(direction):
    return Vector(direction).normalized().to_track_quat("-Z", "Y").to_euler()


def add_light(name, kind, energy, location, direction=None, **extra):
    data = bpy.data.lights.new(name, kind)
    data.energy = energy
    if kind == "SUN":
        data.angle = 0.0
    else:
        data.shadow_soft_size = 0.0
    for key, value in extra.items():
        setattr(data, key, value)
    obj = bpy.data.objects.new(name, data)
    obj.location = location
    if direction is not None:
        obj.rotation_euler = look_rotation(direction)
    bpy.context.scene.collection.objects.link(obj)
    return obj


def build_lights(b):
    fixture = b.mesh("ceiling_light", [lathe_part([(0.2, 0.0), (0.22, 0.03), (0.18, 0.06)], 48, 0, cap_top=True)],
                     ["plain:white"], design="ceiling_light")
    for k, (x, y, watts) in enumerate([(2.6, 3.3, 75), (6.6, 3.3, 75), (11.4, 2.8, 75), (3.5, 8.8, 60), (9.8, 8.8, 60), (13.5, 8.8, 60)]):
        b.place("ceiling_light", fixture, Place(x, y, 0, HEIGHT - 0.06))
        add_light(f"ceiling_point_{k}", "POINT", float(watts), (x, y, HEIGHT - 0.15))
    for k, x in enumerate((12.9, 13.8, 14.7)):
        add_light(f"kitchen_spot_{k}", "SPOT", 40.0, (x, 5.4, HEIGHT - 0.05), (0.0, 0.6, -1.8),
                  spot_size=math.radians(60.0), spot_blend=0.2)
    elevation, azimuth = math.radians(35.0), math.radians(70.0)
    add_light("sun", "SUN", 5.0, (8.0, -4.0, 6.0),
              (math.cos(elevation) * math.cos(azimuth), math.cos(elevation) * math.sin(azimuth), -math.sin(elevation)))


def build_camera():
    data = bpy.data.cameras.new("camera")
    data.lens_unit = "FOV"
    data.angle = math.radians(75.0)
    data.clip_start = 0.05
    data.clip_end = 100.0
    position = Vector((1.6, 1.3, 1.5))
    cam = bpy.data.objects.new("camera", data)
    cam.location = position
    cam.rotation_euler = look_rotation(Vector((11.0, 3.5, 1.0)) - position)
    bpy.context.scene.collection.objects.link(cam)
    bpy.context.scene.camera = cam


# ---------------------------------------------------------------------------------------
# Materials and textures for the requests.

def resolve_materials(b, total_images, size, folder):
    requests = {}
    for mat in b.requests:
        category = mat.name.split(":")[1]
        requests[category] = requests.get(category, 0) + 1
    counts = allocate(requests, total_images)
    pools, n_image, texels = {}, 0, [0]
    for category in CATEGORIES:
        if category not in counts:
            continue
        maps, large, _ = CATEGORIES[category]
        side = size if large else max(16, size // 2)
        pools[category] = []
        for k in range(counts[category]):
            colour, height, rough = PATTERNS[category][int(b.rng.integers(0, len(PATTERNS[category])))](b.rng, side)
            images = {}
            stem = f"{category}_{k:03d}"
            images["colour"] = write_image(f"{stem}_basecolor", colour, folder, jpeg=True, non_colour=False)
            if "normal" in maps:
                images["normal"] = write_image(f"{stem}_normal", normal_map(height, float(b.rng.uniform(2, 6))), folder,
                                               jpeg=False, non_colour=True)
            if "rough" in maps:
                metal = 1.0 if category == "metal" else 0.0
                rgb = np.stack([np.ones_like(rough), np.clip(rough, 0.02, 1), np.full_like(rough, metal)], -1)
                images["rough"] = write_image(f"{stem}_roughness", rgb, folder, jpeg=False, non_colour=True)
            n_image += len(images)
            texels[0] += len(images) * side * side
            pools[category].append(textured(stem, category, images))
        order = b.rng.permutation(len(pools[category]))
        pools[category] = [pools[category][i] for i in order]
    used = {c: 0 for c in pools}
    replacement = {}
    for mat in b.requests:
        category = mat.name.split(":")[1]
        pool = pools[category]
        replacement[mat.name] = pool[used[category] % len(pool)]
        used[category] += 1
    for mesh in bpy.data.meshes:
        for i, slot in enumerate(mesh.materials):
            if slot is not None and slot.name in replacement:
                mesh.materials[i] = replacement[slot.name]
    for mat in b.requests:
        bpy.data.materials.remove(mat)
    return n_image, counts, requests, texels[0]


# ---------------------------------------------------------------------------------------

def export(path):
    bpy.ops.export_scene.gltf(
        filepath=path, export_format="GLTF_SEPARATE", export_texture_dir="", export_image_format="AUTO",
        export_yup=True, export_lights=True, export_cameras=True, export_apply=True,
        export_texcoords=True, export_normals=True, export_tangents=True, export_colors=False,
        export_materials="EXPORT", export_animations=False, export_extras=False,
        export_draco_mesh_compression_enable=False, convert_lighting_mode="SPEC")


def summarise(path, args, seconds, allocation, texels):
    """Re-reads the written glTF: what a loader will see."""
    with open(path) as f:
        doc = json.load(f)
    folder = os.path.dirname(path)
    mesh_tris = []
    for mesh in doc["meshes"]:
        mesh_tris.append(sum(doc["accessors"][p["indices"]]["count"] // 3 for p in mesh["primitives"]))
    nodes = doc["nodes"]
    drawn = sum(mesh_tris[n["mesh"]] for n in nodes if "mesh" in n)
    images = doc.get("images", [])
    by_format, image_bytes = {}, 0
    for image in images:
        file = os.path.join(folder, image["uri"])
        by_format[image["mimeType"]] = by_format.get(image["mimeType"], 0) + 1
        image_bytes += os.path.getsize(file)
    lights = doc.get("extensions", {}).get("KHR_lights_punctual", {}).get("lights", [])
    light_types = {}
    for light in lights:
        light_types[light["type"]] = light_types.get(light["type"], 0) + 1
    camera = next(n for n in nodes if "camera" in n)
    bin_bytes = sum(os.path.getsize(os.path.join(folder, buf["uri"])) for buf in doc["buffers"])
    summary = {
        "file": os.path.basename(path),
        "arguments": {"triangles": args.triangles, "textures": args.textures, "seed": args.seed,
                      "texture_size": args.texture_size},
        "triangles": drawn,
        "unique_triangles": sum(mesh_tris),
        "meshes": len(doc["meshes"]),
        "primitives": sum(len(m["primitives"]) for m in doc["meshes"]),
        "nodes": len(nodes),
        "mesh_nodes": sum("mesh" in n for n in nodes),
        "materials": len(doc.get("materials", [])),
        "textures": len(doc.get("textures", [])),
        "images": len(images),
        "images_by_format": by_format,
        "image_file_bytes": image_bytes,
        "image_texels": texels,
        "texels_as_float_rgba_bytes": texels * 16,
        "buffer_bytes": bin_bytes,
        "materials_per_category": allocation,
        "lights": light_types,
        "camera_translation_gltf": camera.get("translation"),
        "extensions_used": doc.get("extensionsUsed"),
        "extensions_required": doc.get("extensionsRequired"),
        "blender_seconds": seconds,
    }
    with open(os.path.join(folder, os.path.splitext(os.path.basename(path))[0] + "_summary.json"), "w") as f:
        json.dump(summary, f, indent=2)
        f.write("\n")
    print(json.dumps(summary, indent=2))
    return summary


def main():
    args = parse_args()
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    start = time.time()
    bpy.ops.wm.read_factory_settings(use_empty=True)
    bpy.context.scene.render.engine = "CYCLES"
    b = Builder(args.seed)
    build_shell(b)
    living(b)
    dining(b)
    bedroom(b)
    study(b)
    paintings(b)
    build_lights(b)
    build_camera()
    b.bake()
    furniture, unique = b.triangles()
    print(f"make_big_room.py: shell and furniture {furniture} triangles ({unique} unique), {len(b.slots)} decoration slots")
    if furniture >= args.triangles:
        sys.exit(f"make_big_room.py: the furniture alone has {furniture} triangles, more than --triangles {args.triangles}")
    build_decor(b, args.triangles, furniture)
    total, unique = b.triangles()
    print(f"make_big_room.py: {total} triangles ({unique} unique) after decoration")
    scratch = tempfile.mkdtemp(prefix="make_big_room_")
    try:
        n_images, allocation, requests, texels = resolve_materials(b, args.textures, args.texture_size, scratch)
        print(f"make_big_room.py: {n_images} images; materials per category {allocation} (requests {requests})")
        built = time.time() - start
        path = os.path.join(out, args.name + ".gltf")
        export(path)
        exported = time.time() - start - built
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    summarise(path, args, {"build": round(built, 1), "export": round(exported, 1)}, allocation, texels)


main()

#!/usr/bin/env python3
"""Writes shared_mesh.gltf/.bin: five nodes drawing one tetrahedron (flat normals) under a
parent with translation, rotation and uniform scale; one child mirrored (scale -1 on x),
one with non-uniform scale. `gltf-transform instance` turns it into
shared_mesh_instanced.gltf (README.md)."""
import json
import math
import struct
from pathlib import Path

corners = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1)]
faces = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]  # counter-clockwise seen from outside


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return tuple(x / n for x in v)


positions, normals = [], []
for f in faces:
    p = [corners[i] for i in f]
    n = unit(cross(sub(p[1], p[0]), sub(p[2], p[0])))
    positions += p
    normals += [n] * 3
indices = list(range(len(positions)))

bin_data = b"".join(struct.pack("<3f", *p) for p in positions)
bin_data += b"".join(struct.pack("<3f", *n) for n in normals)
bin_data += b"".join(struct.pack("<H", i) for i in indices)


def quat(axis, degrees):
    a = unit(axis)
    s = math.sin(math.radians(degrees) / 2)
    return [a[0] * s, a[1] * s, a[2] * s, math.cos(math.radians(degrees) / 2)]


children = [
    {"name": "a", "mesh": 0},
    {"name": "b", "mesh": 0, "translation": [3, 0, 0], "rotation": quat((1, 0, 0), 90)},
    {"name": "c", "mesh": 0, "translation": [0, 3, 0], "scale": [1, 0.5, 2]},
    {"name": "mirrored", "mesh": 0, "translation": [0, 0, 3], "scale": [-1, 1, 1]},
    {"name": "e", "mesh": 0, "translation": [3, 3, 3], "rotation": quat((1, 1, 1), 45), "scale": [0.5, 0.5, 0.5]},
]
n = len(positions)
doc = {
    "asset": {"version": "2.0", "generator": "make_shared_mesh.py (phyir tests)"},
    "scene": 0,
    "scenes": [{"nodes": [0]}],
    "nodes": [{"name": "group", "translation": [1, 2, 3], "rotation": quat((0, 1, 0), 30), "scale": [2, 2, 2],
               "children": list(range(1, 1 + len(children)))}] + children,
    "meshes": [{"name": "tetrahedron", "primitives": [{"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2}]}],
    "accessors": [
        {"bufferView": 0, "componentType": 5126, "count": n, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 1]},
        {"bufferView": 1, "componentType": 5126, "count": n, "type": "VEC3"},
        {"bufferView": 2, "componentType": 5123, "count": n, "type": "SCALAR"},
    ],
    "bufferViews": [
        {"buffer": 0, "byteOffset": 0, "byteLength": 12 * n},
        {"buffer": 0, "byteOffset": 12 * n, "byteLength": 12 * n},
        {"buffer": 0, "byteOffset": 24 * n, "byteLength": 2 * n},
    ],
    "buffers": [{"uri": "shared_mesh.bin", "byteLength": len(bin_data)}],
}
here = Path(__file__).parent
(here / "shared_mesh.bin").write_bytes(bin_data)
(here / "shared_mesh.gltf").write_text(json.dumps(doc, indent=1) + "\n")

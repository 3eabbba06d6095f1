#!/usr/bin/env python3
"""Writes emissive_enclosure.gltf (+ .bin) beside this script: a closed 4 x 2.6 x 4 m room
whose six walls all emit radiance 1 and are black dielectrics (base colour 0, roughness 1,
metalness 0: only the ~4% Fresnel lobe reflects), like enclosure() of
tests/probes/probe_renderer_test.cpp. Every probe texel sees an emitter; the probes' exact
answer is 1 + the walls' Fresnel reflection (docs/probes-accuracy.md, "Rooms that are all light").
Its camera stands off-centre inside. Usage: python3 make_emissive_enclosure.py [OUT_DIR]"""
import json
import os
import struct
import sys

LO = (-2.0, 0.0, -2.0)
HI = (2.0, 2.6, 2.0)
CAMERA = (0.3, 1.2, 0.2)


def faces():
    """Six quads (corner, edge u, edge v); main() turns each to face the room's inside."""
    (x0, y0, z0), (x1, y1, z1) = LO, HI
    dx, dy, dz = x1 - x0, y1 - y0, z1 - z0
    return [
        ((x0, y0, z0), (0, 0, dz), (0, dy, 0)),
        ((x1, y0, z0), (0, dy, 0), (0, 0, dz)),
        ((x0, y0, z0), (dx, 0, 0), (0, 0, dz)),
        ((x0, y1, z0), (0, 0, dz), (dx, 0, 0)),
        ((x0, y0, z0), (0, dy, 0), (dx, 0, 0)),
        ((x0, y0, z1), (dx, 0, 0), (0, dy, 0)),
    ]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
    centre = tuple((a + b) / 2 for a, b in zip(LO, HI))
    positions, normals, indices = [], [], []
    for corner, u, v in faces():
        n = cross(u, v)
        length = sum(c * c for c in n) ** 0.5
        n = tuple(c / length for c in n)
        # Inward: the normal points from the face towards the room's centre.
        to_centre = tuple(c - p for c, p in zip(centre, corner))
        if sum(a * b for a, b in zip(n, to_centre)) < 0:
            u, v, n = v, u, tuple(-c for c in n)
        base = len(positions)
        for a, b in ((0, 0), (1, 0), (1, 1), (0, 1)):
            positions.append(tuple(corner[k] + a * u[k] + b * v[k] for k in range(3)))
            normals.append(n)
        indices += [base, base + 1, base + 2, base, base + 2, base + 3]
    blob = b"".join(struct.pack("<3f", *p) for p in positions)
    blob += b"".join(struct.pack("<3f", *n) for n in normals)
    blob += b"".join(struct.pack("<I", i) for i in indices)
    nv = len(positions)
    doc = {
        "asset": {"version": "2.0", "generator": "bench/scenes/make_emissive_enclosure.py"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1]}],
        "nodes": [{"name": "enclosure", "mesh": 0},
                  {"name": "camera", "camera": 0, "translation": list(CAMERA)}],
        "cameras": [{"type": "perspective", "perspective": {"yfov": 1.2, "znear": 0.01}}],
        "meshes": [{"name": "enclosure", "primitives": [
            {"attributes": {"POSITION": 0, "NORMAL": 1}, "indices": 2, "material": 0}]}],
        "materials": [{"name": "black_emitting_wall",
                       "pbrMetallicRoughness": {"baseColorFactor": [0, 0, 0, 1],
                                                "metallicFactor": 0, "roughnessFactor": 1},
                       "emissiveFactor": [1, 1, 1]}],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": nv, "type": "VEC3",
             "min": list(LO), "max": list(HI)},
            {"bufferView": 1, "componentType": 5126, "count": nv, "type": "VEC3"},
            {"bufferView": 2, "componentType": 5125, "count": len(indices), "type": "SCALAR"},
        ],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": 12 * nv},
            {"buffer": 0, "byteOffset": 12 * nv, "byteLength": 12 * nv},
            {"buffer": 0, "byteOffset": 24 * nv, "byteLength": 4 * len(indices)},
        ],
        "buffers": [{"uri": "emissive_enclosure.bin", "byteLength": len(blob)}],
    }
    with open(os.path.join(out, "emissive_enclosure.bin"), "wb") as f:
        f.write(blob)
    with open(os.path.join(out, "emissive_enclosure.gltf"), "w") as f:
        json.dump(doc, f, indent=1)
        f.write("\n")


if __name__ == "__main__":
    main()

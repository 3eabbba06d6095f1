"""Writes a 1 m cube standing on y = 0 as a self-contained glTF (embedded buffer) to argv[1],
with a red rough material unless argv[2] == "plain": visible from every side, for the
insertion scripts."""
import base64
import json
import struct
import sys

p = [(x, y, z) for x in (-.5, .5) for y in (0, 1) for z in (-.5, .5)]
quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
idx = [i for a, b, c, d in quads for i in (a, b, c, a, c, d)]
data = b"".join(struct.pack("<3f", *v) for v in p) + struct.pack(f"<{len(idx)}H", *idx)
uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
primitive = {"attributes": {"POSITION": 0}, "indices": 1}
gltf = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [primitive]}],
        "buffers": [{"byteLength": len(data), "uri": uri}],
        "bufferViews": [{"buffer": 0, "byteLength": 96, "target": 34962},
                        {"buffer": 0, "byteOffset": 96, "byteLength": 72, "target": 34963}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                       "min": [-.5, 0, -.5], "max": [.5, 1, .5]},
                      {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}]}
if len(sys.argv) < 3 or sys.argv[2] != "plain":
    primitive["material"] = 0
    gltf["materials"] = [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.2, 1], "metallicFactor": 0,
                                                    "roughnessFactor": 0.5}}]
json.dump(gltf, open(sys.argv[1], "w"))

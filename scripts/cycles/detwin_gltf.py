#!/usr/bin/python3
"""Writes a copy of a glTF without twin triangles: of every set of triangles with the same three
vertex positions (world space, to 0.1 mm; in practice a triangle and its copy of opposite
winding, a way some models make a sheet double-sided), only the first is kept.

    detwin_gltf.py IN.gltf OUT_DIR

OUT_DIR gets OUT.gltf (IN's name with _detwinned), OUT.bin (the new index arrays only) and
symbolic links to IN's buffers and images, so the copy reads the same data. Prints what it
dropped per mesh. Used in docs/cycles-comparison-results.md ("Furnished apartment at night").
"""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from compare import node_matrix  # noqa: E402

COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
TYPES = {5126: np.float32, 5125: np.uint32, 5123: np.uint16, 5121: np.uint8}


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src, out_dir = sys.argv[1], sys.argv[2]
    base = os.path.dirname(os.path.abspath(src))
    gltf = json.load(open(src))
    buffers = [open(os.path.join(base, b["uri"]), "rb").read() for b in gltf["buffers"]]

    def accessor(index):
        a = gltf["accessors"][index]
        view = gltf["bufferViews"][a["bufferView"]]
        n = COMPONENTS[a["type"]]
        if view.get("byteStride", 0) not in (0, n * np.dtype(TYPES[a["componentType"]]).itemsize):
            sys.exit(f"{src}: accessor {index} is interleaved (byteStride {view['byteStride']}), not supported")
        data = np.frombuffer(buffers[view["buffer"]], dtype=TYPES[a["componentType"]], count=a["count"] * n,
                             offset=view.get("byteOffset", 0) + a.get("byteOffset", 0))
        return data.reshape(a["count"], n) if n > 1 else data

    seen, drop, triangles = set(), {}, {}
    scene = gltf["scenes"][gltf.get("scene", 0)]
    stack = [(i, np.eye(4)) for i in scene["nodes"]]
    while stack:
        index, parent = stack.pop()
        node = gltf["nodes"][index]
        world = parent @ node_matrix(node)
        stack += [(c, world) for c in node.get("children", [])]
        if "mesh" not in node:
            continue
        for k, primitive in enumerate(gltf["meshes"][node["mesh"]]["primitives"]):
            if primitive.get("mode", 4) != 4 or "indices" not in primitive:
                continue
            p = accessor(primitive["attributes"]["POSITION"]).astype(np.float64)
            p = (np.c_[p, np.ones(len(p))] @ world.T)[:, :3]
            tris = accessor(primitive["indices"]).reshape(-1, 3)
            triangles[(node["mesh"], k)] = tris
            keys = np.round(p[tris] * 1e4).astype(np.int64)
            for t in range(len(tris)):
                key = tuple(sorted(map(tuple, keys[t])))
                if key in seen:
                    drop.setdefault((node["mesh"], k), []).append(t)
                else:
                    seen.add(key)

    name = os.path.splitext(os.path.basename(src))[0] + "_detwinned"
    os.makedirs(out_dir, exist_ok=True)
    extra = bytearray()
    for (mesh, k), dropped in sorted(drop.items()):
        indices = np.delete(triangles[(mesh, k)], dropped, axis=0).astype(np.uint32).ravel()
        gltf["bufferViews"].append({"buffer": len(buffers), "byteOffset": len(extra),
                                    "byteLength": indices.nbytes, "target": 34963})
        gltf["accessors"].append({"bufferView": len(gltf["bufferViews"]) - 1, "componentType": 5125,
                                  "count": int(indices.size), "type": "SCALAR"})
        gltf["meshes"][mesh]["primitives"][k]["indices"] = len(gltf["accessors"]) - 1
        extra += indices.tobytes()
        print(f"mesh {mesh} ({gltf['meshes'][mesh].get('name', '')}) primitive {k}: dropped {len(dropped)} "
              f"of {len(triangles[(mesh, k)])} triangles")
    gltf["buffers"].append({"uri": name + ".bin", "byteLength": len(extra)})
    with open(os.path.join(out_dir, name + ".bin"), "wb") as f:
        f.write(extra)
    for uri in [b["uri"] for b in gltf["buffers"][:-1]] + [i["uri"] for i in gltf.get("images", []) if "uri" in i]:
        link = os.path.join(out_dir, uri)
        if not os.path.exists(link):
            os.makedirs(os.path.dirname(link) or out_dir, exist_ok=True)
            os.symlink(os.path.join(base, uri), link)
    with open(os.path.join(out_dir, name + ".gltf"), "w") as f:
        json.dump(gltf, f)
    print(f"{src}: dropped {sum(len(d) for d in drop.values())} twin triangles, wrote {out_dir}/{name}.gltf")


if __name__ == "__main__":
    main()

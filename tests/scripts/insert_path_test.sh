#!/usr/bin/env bash
# `phyir insert --path`: dynamic insertion end to end on a small render of a generated room. A
# box moved over the floor in 3 steps: one complete insertion folder per frame, the contact
# sheet, and path.gif holding the 3 frames; the object is in every frame and moves.
#   $1 = phyir binary, $2 = scratch folder (emptied).
source "$(dirname "${BASH_SOURCE[0]}")/lib/prologue.sh"

"$phyir" --log-level warn scenes generate --out rooms --count 1 --seed 7 --preset mini
"$phyir" --log-level warn render rooms/room_0.gltf --out view --width 64 --height 32 --spp 4 --probes \
  --probe-grid 16x32 --probe-res 4x8 --probe-spp 1 --threads 2
/usr/bin/python3 - <<'PY'
import base64, json, struct
p = [(x, y, z) for x in (-.5, .5) for y in (0, 1) for z in (-.5, .5)]
quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
idx = [i for a, b, c, d in quads for i in (a, b, c, a, c, d)]
data = b"".join(struct.pack("<3f", *v) for v in p) + struct.pack(f"<{len(idx)}H", *idx)
uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
json.dump({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "buffers": [{"byteLength": len(data), "uri": uri}],
           "bufferViews": [{"buffer": 0, "byteLength": 96, "target": 34962},
                           {"buffer": 0, "byteOffset": 96, "byteLength": 72, "target": 34963}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                          "min": [-.5, 0, -.5], "max": [.5, 1, .5]},
                         {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}]},
          open("box.gltf", "w"))
PY
"$phyir" --log-level warn insert view box.gltf --pixel 28 28 --path 36 28 --steps 3 --scale 0.3 --spp 2 \
  --max-bounces 2 --threads 2 --out moved
for k in 000 001 002; do
  for f in composite.exr composite.png mask.png insert.json; do [ -s "moved/frame_$k/$f" ] || die "frame_$k/$f missing"; done
done
[ -s moved/contact_sheet.png ] || die "no contact sheet"
/usr/bin/python3 - <<'PY' || die "path.gif or the frames are wrong"
import numpy as np
import OpenImageIO as oiio
gif = oiio.ImageInput.open("moved/path.gif")
assert gif, "path.gif unreadable"
n = 0
while gif.seek_subimage(n, 0):
    n += 1
assert n == 3, f"path.gif holds {n} frames"
centres = []
for k in range(3):
    mask = oiio.ImageBuf(f"moved/frame_{k:03d}/mask.png").get_pixels(oiio.FLOAT)[..., 0] > 0.5
    assert mask.any(), f"frame {k}: no object pixel"
    centres.append(np.nonzero(mask)[1].mean())
assert centres[0] < centres[1] < centres[2], f"the object does not move right: {centres}"
PY
echo "insert --path: OK"

#!/usr/bin/env bash
# `phyir insert --path`: dynamic insertion end to end on a small render of a generated room. A
# box moved over the floor in 3 steps: one complete insertion folder per frame, the contact
# sheet, and path.gif holding the 3 frames; the object is in every frame and moves.
#   $1 = phyir binary, $2 = scratch folder (emptied).
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)  # before the prologue changes directory
source "$here/lib/prologue.sh"

"$phyir" --log-level warn scenes generate --out rooms --count 1 --seed 7 --preset mini
"$phyir" --log-level warn render rooms/room_0.gltf --out view --width 64 --height 32 --spp 4 --probes \
  --probe-grid 16x32 --probe-res 4x8 --probe-spp 1 --threads 2
/usr/bin/python3 "$here/lib/cube_gltf.py" box.gltf plain
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

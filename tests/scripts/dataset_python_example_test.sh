#!/usr/bin/env bash
# scripts/load_dataset_example.py (docs/python.md) on a tiny dataset with probes (2 mini rooms
# x 2 views): it prints the shapes of every map and of the probes reshaped to [H, W, h, w, 3];
# the arrays it saves equal the files as OpenImageIO reads them, probe (i, j) is the mosaic's
# block at rows i h.., columns j w.. (checked here with plain indexing); it refuses a view
# whose file no longer matches its checksum, an unfinished dataset (no manifest) and an
# out-of-range view, with a message and a non-zero exit.
#   $1 = phyir binary, $2 = scratch folder (emptied).
set -euo pipefail
root=${PHYIR_SOURCE_ROOT:-$(cd "$(dirname "$0")/../.." && pwd)}
example=$root/scripts/load_dataset_example.py
source "$(dirname "${BASH_SOURCE[0]}")/lib/prologue.sh"
/usr/bin/python3 -c 'import OpenImageIO, numpy' || die "needs python3-openimageio and python3-numpy (scripts/install_deps.sh)"

"$phyir" --log-level warn scenes generate --out rooms --count 2 --seed 5 --preset mini
"$phyir" --log-level warn dataset generate --scenes rooms --out data --preset tiny --views-per-scene 2 \
  --split 1,0,0 --threads 2 --quiet

/usr/bin/python3 "$example" data --split train --view 3 --save view.npz > out.txt || { cat out.txt; die "example failed"; }
cat out.txt
grep -q "data/manifest.json: 4 views train 4, val 0, test 0" out.txt || die "view counts not printed"
grep -q "^view room_1/v001 (split train" out.txt || die "--view 3 of train should be room_1/v001"
for expected in "color *(32, 64, 3)" "depth *(32, 64, 1)" "normal *(32, 64, 3)" "basecolor *(32, 64, 3)" \
  "roughness *(32, 64, 1)" "metalness *(32, 64, 1)" "mask_geometry *(32, 64, 1)" "mask_emissive *(32, 64, 1)" \
  "mask_transparent *(32, 64, 1)" "input *(32, 64, 3)" "probes *(8, 16, 4, 8, 3)" "probe_mask *(8, 16, 1)"; do
  grep -q "^  $expected" out.txt || die "no line '$expected'"
done

# The saved arrays against the files, read independently; probes by explicit block indexing.
/usr/bin/python3 - data/views/room_1/v001 view.npz <<'PY'
import sys
import numpy as np
import OpenImageIO as oiio
folder, saved = sys.argv[1], np.load(sys.argv[2])
def read(name):
    buf = oiio.ImageBuf(f"{folder}/{name}")
    return np.asarray(buf.get_pixels(oiio.FLOAT))
for name in ["color", "depth", "normal", "basecolor", "roughness", "metalness", "mask_geometry",
             "mask_emissive", "mask_transparent"]:
    assert np.array_equal(saved[name], read(name + ".exr")), name
assert np.array_equal(saved["input"], read("input.png")), "input"
mosaic, probes = read("probes.exr"), saved["probes"]
for i in range(8):
    for j in range(16):
        block = mosaic[i * 4:(i + 1) * 4, j * 8:(j + 1) * 8, :3]
        assert np.array_equal(probes[i, j], block), (i, j)
assert probes.min() >= 0 and np.isfinite(probes).all()
print("arrays match the files")
PY

# Refusals.
if /usr/bin/python3 "$example" data --split train --view 4 > bad.txt 2>&1; then die "--view 4 of 4 accepted"; fi
grep -q "out of range" bad.txt || { cat bad.txt; die "no out-of-range message"; }
mkdir unfinished
if /usr/bin/python3 "$example" unfinished > bad.txt 2>&1; then die "a folder without manifest accepted"; fi
grep -q "unfinished/manifest.json: missing" bad.txt || { cat bad.txt; die "no message naming the manifest"; }
printf 'x' >> data/views/room_0/v000/depth.exr
if /usr/bin/python3 "$example" data --view 0 > bad.txt 2>&1; then die "a damaged file loaded"; fi
grep -q "depth.exr: does not match the manifest" bad.txt || { cat bad.txt; die "no checksum message"; }
echo "dataset_python_example_test: OK"

#!/usr/bin/env bash
# `phyir render` end to end on a generated `hard` room (mirrors, metals, glass, a small
# bright bulb, thin geometry): every promised file exists, none holds NaN or Inf, labels
# are in range, render.json names the effects that ran; same seed gives identical files
# with --threads 1 and 2; bad flags exit non-zero with a message and leave no output.
#   $1 = phyir binary, $2 = scratch folder (emptied).
set -euo pipefail
phyir=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
die() { echo "FAIL: $*" >&2; exit 1; }

"$phyir" --log-level warn scenes generate --out "$work/rooms" --count 1 --seed 3 --preset hard
scene=$(ls "$work"/rooms/*.gltf | head -n 1)
"$phyir" --log-level warn render "$scene" --out "$work/a" --width 96 --height 48 --spp 8 --seed 5 --threads 1 --quiet
"$phyir" --log-level warn render "$scene" --out "$work/b" --width 96 --height 48 --spp 8 --seed 5 --threads 2 --quiet

for f in color.exr color.png depth.exr normal.exr basecolor.exr roughness.exr metalness.exr \
         mask_emissive.exr mask_transparent.exr mask_geometry.exr render.json; do
  [ -s "$work/a/$f" ] || die "missing $f"
done
for f in color.exr depth.exr normal.exr basecolor.exr roughness.exr metalness.exr; do
  cmp -s "$work/a/$f" "$work/b/$f" || die "$f differs between --threads 1 and --threads 2"
done
ls -a "$work/a" | grep -q partial && die "temporary files left behind"

/usr/bin/python3 - "$work/a" <<'PY' || die "output check failed"
import json, sys
import numpy as np
import OpenImageIO as oiio
d = sys.argv[1]
def read(name):
    img = oiio.ImageInput.open(f"{d}/{name}")
    assert img, f"{name}: {oiio.geterror()}"
    px = img.read_image("float")
    img.close()
    return np.asarray(px)
for name in ["color", "depth", "normal", "basecolor", "roughness", "metalness",
             "mask_emissive", "mask_transparent", "mask_geometry"]:
    a = read(name + ".exr")
    assert np.isfinite(a).all(), f"{name}.exr holds NaN or Inf"
    assert (a >= -1.0).all(), f"{name}.exr below -1"
geometry = read("mask_geometry.exr")[..., 0] > 0
n = read("normal.exr")
lengths = np.linalg.norm(n, axis=-1)[geometry]
assert np.allclose(lengths, 1.0, atol=1e-3), "normals are not unit length"
for name in ["roughness", "metalness", "basecolor"]:
    a = read(name + ".exr")
    assert a.min() >= 0 and a.max() <= 1, f"{name} outside [0,1]"
assert (read("depth.exr")[..., 0][geometry] > 0).all(), "zero depth on geometry"
assert (read("color.exr") >= 0).all(), "negative radiance"
assert read("mask_emissive.exr").max() == 1, "the room's lights are not in mask_emissive"
r = json.load(open(f"{d}/render.json"))
assert r["counters"]["nonfinite_samples_caught"] == 0, r["counters"]
e = r["effects"]
assert e["emitter_sampling"] and e["transmission"] and e["mirrors"], e
assert r["settings"]["seed"] == 5 and r["settings"]["spp"] == 8
assert "Euclidean" in r["conventions"]["depth"]
# color.png: auto exposure by default, recorded (core/auto_exposure.h's rule, recomputed here).
assert r["settings"]["exposure"] == "auto", r["settings"]["exposure"]
c = read("color.exr")[..., :3].ravel()
v = np.sort(c)[min(c.size - 1, int(0.95 * c.size))]
assert abs(r["color_png"]["percentile_value"] - v) <= 1e-6 * max(v, 1.0), (r["color_png"], v)
assert abs(r["color_png"]["exposure_stops"] - np.log2(0.9 / v)) < 1e-4, r["color_png"]
PY
"$phyir" --log-level warn render "$scene" --out "$work/fixed" --width 32 --height 16 --spp 1 --exposure -1.5 --quiet
grep -q '"exposure_stops": -1.5' "$work/fixed/render.json" || die "--exposure -1.5 not recorded"
if "$phyir" render "$scene" --out "$work/bad" --exposure bright 2> "$work/err.txt"; then die "--exposure bright accepted"; fi
grep -q -- "--exposure 'bright'" "$work/err.txt" || die "error does not name --exposure: $(cat "$work/err.txt")"

# Bad input: clear message, non-zero exit, no output folder that looks complete.
if "$phyir" render "$scene" --out "$work/bad" --spp 0 2> "$work/err.txt"; then die "--spp 0 accepted"; fi
grep -q -- "--spp" "$work/err.txt" || die "error does not name --spp: $(cat "$work/err.txt")"
[ ! -e "$work/bad/render.json" ] || die "render.json written for a failed render"
if "$phyir" render "$scene" --out "$work/bad" --camera 1,2 2> "$work/err.txt"; then die "--camera 1,2 accepted"; fi
grep -q "X,Y,Z" "$work/err.txt" || die "error does not explain --camera"
printf '{"asset": {"version": "2.0"}, "meshes": [' > "$work/broken.gltf"
if "$phyir" render "$work/broken.gltf" --out "$work/bad" 2> "$work/err.txt"; then die "broken glTF accepted"; fi
grep -q "broken.gltf" "$work/err.txt" || die "error does not name the file"
echo "render_hard_room_test: ok"

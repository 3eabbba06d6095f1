#!/usr/bin/env bash
# `phyir render --probes` end to end on a generated `mini` room with a small grid: the four
# probe files exist with the promised sizes, hold no NaN, Inf or negative radiance, the mask
# is 1 exactly where a probe is a valid label, render.json has its "probes" block; same seed
# gives identical probes with --threads 1 and 2 (with --probe-error too, whose passes
# render.json reports); turning probes on leaves color.exr as it was and writes nothing of
# the probes when off; bad probe flags fail with a message.
#   $1 = phyir binary, $2 = scratch folder (emptied).
set -euo pipefail
phyir=$1
work=$2
rm -rf "$work"
mkdir -p "$work"
die() { echo "FAIL: $*" >&2; exit 1; }

"$phyir" --log-level warn scenes generate --out "$work/rooms" --count 1 --seed 2 --preset mini
scene=$(ls "$work"/rooms/*.gltf | head -n 1)
common=(--width 64 --height 32 --spp 4 --seed 7 --quiet)
probes=(--probes --probe-grid 8x16 --probe-res 8x16 --probe-spp 2 --probe-cache-spp 16)
"$phyir" --log-level warn render "$scene" --out "$work/a" "${common[@]}" "${probes[@]}" --threads 1
"$phyir" --log-level warn render "$scene" --out "$work/b" "${common[@]}" "${probes[@]}" --threads 2
"$phyir" --log-level warn render "$scene" --out "$work/plain" "${common[@]}" --threads 2

for f in probes.exr probe_position.exr probe_normal.exr probe_mask.exr render.json; do
  [ -s "$work/a/$f" ] || die "missing $f"
done
for f in probes.exr probe_position.exr probe_normal.exr probe_mask.exr color.exr; do
  cmp -s "$work/a/$f" "$work/b/$f" || die "$f differs between --threads 1 and --threads 2"
done
cmp -s "$work/a/color.exr" "$work/plain/color.exr" || die "--probes changed color.exr"
ls "$work/plain" | grep -q probe && die "probe files written without --probes"

/usr/bin/python3 - "$work/a" "$work/plain" <<'PY' || die "output check failed"
import json, sys
import numpy as np
import OpenImageIO as oiio
d, plain = sys.argv[1], sys.argv[2]
def read(name):
    img = oiio.ImageInput.open(f"{d}/{name}")
    assert img, f"{name}: {oiio.geterror()}"
    spec = img.spec()
    px = np.asarray(img.read_image("float"))
    img.close()
    return px, spec
probes, spec = read("probes.exr")
assert probes.shape == (8 * 8, 16 * 16, 3), probes.shape
assert list(spec.channelnames) == ["R", "G", "B"], spec.channelnames
position, spec = read("probe_position.exr")
assert position.shape == (8, 16, 3) and list(spec.channelnames) == ["X", "Y", "Z"]
normal, _ = read("probe_normal.exr")
mask, _ = read("probe_mask.exr")
assert mask.shape == (8, 16, 1), mask.shape
mask = mask[..., 0]
for name, a in [("probes", probes), ("position", position), ("normal", normal), ("mask", mask)]:
    assert np.isfinite(a).all(), f"{name} holds NaN or Inf"
assert (probes >= 0).all(), "negative radiance in probes.exr"
assert set(np.unique(mask)) <= {0.0, 1.0}, np.unique(mask)
# A closed mini room from its camera: every probe sees a surface, most are valid labels.
assert mask.mean() > 0.8, f"only {mask.mean():.2f} of the probes are valid"
seen = np.linalg.norm(normal, axis=-1) > 0
assert np.allclose(np.linalg.norm(normal[seen], axis=-1), 1.0, atol=1e-4), "probe normals not unit"
assert (mask[~seen] == 0).all(), "a probe that sees nothing is marked valid"
# Valid probes are lit: no all-black probe.
blocks = probes.reshape(8, 8, 16, 16, 3).transpose(0, 2, 1, 3, 4).reshape(8, 16, -1)
assert (blocks[mask > 0].max(axis=-1) > 0).all(), "a valid probe is black"
r = json.load(open(f"{d}/render.json"))
p = r["probes"]
assert p["grid"] == [8, 16] and p["resolution"] == [8, 16] and p["spp"] == 2, p
assert p["mode"] == "cache" and abs(p["origin_offset_m"] - 0.01) < 1e-6, p
assert p["seconds"]["total"] > 0 and p["rays"] > 0, p
c = p["counts"]
assert c["probes"] == 128 and c["valid"] + c["invalid"] == 128 and c["valid"] == int(mask.sum()), c
assert p["nonfinite_samples_caught"] == 0, p
assert "probe_seconds" in r["timings"], r["timings"]
assert "probes.exr" in r["files"], r["files"]
assert "probes" not in json.load(open(f"{plain}/render.json")), "probes block without --probes"
PY

# An error target: more passes where the noise is, reported in render.json, the same output
# whatever the thread count.
target=(--probe-error 0.02)
"$phyir" --log-level warn render "$scene" --out "$work/t1" "${common[@]}" "${probes[@]}" "${target[@]}" --threads 1
"$phyir" --log-level warn render "$scene" --out "$work/t2" "${common[@]}" "${probes[@]}" "${target[@]}" --threads 2
for f in probes.exr probe_stderr.exr; do
  cmp -s "$work/t1/$f" "$work/t2/$f" || die "$f with --probe-error differs between --threads 1 and 2"
done
/usr/bin/python3 - "$work/a" "$work/t1" <<'PY' || die "error target check failed"
import json, sys
once = json.load(open(f"{sys.argv[1]}/render.json"))["probes"]
more = json.load(open(f"{sys.argv[2]}/render.json"))["probes"]
assert "target_relative" not in once["error"] and once["error"]["estimated_relative"] > 0.02, once["error"]
e = more["error"]
assert abs(e["target_relative"] - 0.02) < 1e-6 and e["passes"] > 1 and e["refined_probes"] > 0, e
assert e["estimated_relative"] <= 0.02 * (1 + 1e-5) or e["passes"] == 16, e
assert e["estimated_relative"] < once["error"]["estimated_relative"], (e, once["error"])
assert more["target_error"] == 0.02 or abs(more["target_error"] - 0.02) < 1e-6, more
PY

# Bad probe flags: a clear message, a non-zero exit, no render.json.
if "$phyir" render "$scene" --out "$work/bad" --probes --probe-grid 8 2> "$work/err.txt"; then die "--probe-grid 8 accepted"; fi
grep -q -- "--probe-grid" "$work/err.txt" || die "error does not name --probe-grid: $(cat "$work/err.txt")"
if "$phyir" render "$scene" --out "$work/bad" --probes --probe-mode fast 2> "$work/err.txt"; then die "--probe-mode fast accepted"; fi
grep -q -- "--probe-mode" "$work/err.txt" || die "error does not name --probe-mode"
if "$phyir" render "$scene" --out "$work/bad" --probes --probe-spp 0 2> "$work/err.txt"; then die "--probe-spp 0 accepted"; fi
for bad in "--probe-spread-threshold 0" "--probe-cache-direct-cells -1" "--probe-share-radius 5" "--probe-share-parallax 0" \
           "--probe-error -0.1"; do
  flag=${bad%% *}
  # shellcheck disable=SC2086
  if "$phyir" render "$scene" --out "$work/bad" --probes $bad 2> "$work/err.txt"; then die "$bad accepted"; fi
  grep -q -- "$flag" "$work/err.txt" || die "error does not name $flag: $(cat "$work/err.txt")"
done
[ ! -e "$work/bad/render.json" ] || die "render.json written for a failed render"
echo "render_probes_test: ok"

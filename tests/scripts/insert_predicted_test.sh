#!/usr/bin/env bash
# `phyir insert` under the network's lighting, end to end: a tiny dataset view, a network
# trained for a step (its weights do not matter here, only that its outputs are the toolkit's
# `phyir infer` folder), the object inserted into the view lit by the predicted probes, then
# into the view with the prediction's maps (`--maps`: depth, normals and materials predicted
# too), and into the user's own panorama (the infer folder as the view: its record names the
# panorama, decoded to the probes' unit). Checks the outputs, insert.json's record of the lighting, and that the
# composite is finite, non-negative, covers some pixels and differs from the background.
#   $1 = phyir binary, $2 = scratch folder (emptied).
root=${PHYIR_SOURCE_ROOT:-$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)}
source "$(dirname "${BASH_SOURCE[0]}")/lib/prologue.sh"
export OMP_WAIT_POLICY=passive
if "$phyir" train --help 2>&1 | grep -q "not built"; then
  echo "SKIP: phyir built without the model (-DPHYIR_BUILD_MODEL=OFF)"; exit 0
fi

"$phyir" --log-level warn scenes generate --out rooms --count 1 --seed 7 --preset mini
"$phyir" --log-level warn dataset generate --scenes rooms --out data --preset tiny --views-per-scene 1 \
  --split 1,0,0 --seed 1 --threads 2 --quiet
view=$(dirname "$(find data -name view.json | head -1)")
[ -d "$view" ] || die "the dataset has no view"
net=(--seed 1 --threads 1 --quiet --input-height 32 --input-width 64 --render-height 16 --render-width 32
     --probe-height 4 --probe-width 8 --diffuse-samples 8 --specular-samples 4 --width-divisor 4)
"$phyir" --log-level warn train --data data --out lnet --stage lnet --epochs 1 --batch 1 "${net[@]}"
"$phyir" --log-level warn infer --model lnet/checkpoint.pt --input "$view/input.png" --out pred --threads 1
for f in probes.exr probe_mask.exr depth.exr normal.exr basecolor.exr; do
  [ -s "pred/$f" ] || die "phyir infer wrote no $f"
done

# A 1 m cube (scaled to 0.3 m below), embedded buffer: visible from every side.
/usr/bin/python3 - <<'PY'
import base64, json, struct
p = [(x, y, z) for x in (-.5, .5) for y in (0, 1) for z in (-.5, .5)]
quads = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
idx = [i for a, b, c, d in quads for i in (a, b, c, a, c, d)]
data = b"".join(struct.pack("<3f", *v) for v in p) + struct.pack(f"<{len(idx)}H", *idx)
uri = "data:application/octet-stream;base64," + base64.b64encode(data).decode()
json.dump({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "material": 0}]}],
           "materials": [{"pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.2, 0.2, 1], "metallicFactor": 0,
                                                    "roughnessFactor": 0.5}}],
           "buffers": [{"byteLength": len(data), "uri": uri}],
           "bufferViews": [{"buffer": 0, "byteLength": 96, "target": 34962},
                           {"buffer": 0, "byteOffset": 96, "byteLength": 72, "target": 34963}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": 8, "type": "VEC3",
                          "min": [-.5, 0, -.5], "max": [.5, 1, .5]},
                         {"bufferView": 1, "componentType": 5123, "count": 36, "type": "SCALAR"}]},
          open("cube.gltf", "w"))
PY
object=cube.gltf
read -r width height < <(/usr/bin/python3 -c "import OpenImageIO as o;s=o.ImageInput.open('$view/color.exr').spec();print(s.width,s.height)")
x=$((width / 2)); y=$((height * 7 / 8))  # ahead of the camera, low: the floor
common=(--pixel "$x" "$y" --scale 0.3 --spp 4 --max-bounces 2 --threads 2)
"$phyir" --log-level warn insert "$view" "$object" "${common[@]}" --lighting predicted --predicted pred --out ins_pred
"$phyir" --log-level warn insert "$view" "$object" "${common[@]}" --lighting predicted --predicted pred --maps pred \
  --out ins_maps
# The user's own panorama: the infer folder is the view (its record names the panorama).
"$phyir" --log-level warn insert pred "$object" "${common[@]}" --lighting predicted --predicted pred --out ins_user
for out in ins_pred ins_maps ins_user; do
  for f in composite.exr composite.png mask.png insert.json; do [ -s "$out/$f" ] || die "$out/$f missing"; done
done
/usr/bin/python3 - "$view" <<'PY' || die "the predicted insertion's record or composite is wrong"
import json, sys
import numpy as np
import OpenImageIO as oiio
view = sys.argv[1]
def read(path):
    image = oiio.ImageBuf(path)
    return image.get_pixels(oiio.FLOAT)
for out in ("ins_pred", "ins_maps", "ins_user"):
    record = json.load(open(f"{out}/insert.json"))
    lighting = record["lighting"]
    assert lighting["source"] == "predicted", lighting
    assert lighting["probes"].rstrip("/").endswith("pred"), lighting
    assert lighting["spatially_varying"], lighting
    composite = read(f"{out}/composite.exr")
    if out == "ins_user":  # the background is input.png decoded, in absolute units
        background = read(f"{view}/input.png")[..., :3]
        background = np.where(background <= 0.04045, background / 12.92, ((background + 0.055) / 1.055) ** 2.4)
        background /= 2.0 ** json.load(open("pred/infer.json"))["radiance"]["exposure_stops"]
        close = np.isclose(composite, background, rtol=1e-2, atol=1e-4).all(axis=2)
        assert close.mean() > 0.9, f"the background is not the decoded panorama ({close.mean():.2f} of pixels)"
    else:
        background = read(f"{view}/color.exr")
    assert np.isfinite(composite).all() and (composite >= 0).all(), out
    changed = np.abs(composite - background).max(axis=2) > 0
    mask = read(f"{out}/mask.png")[..., 0] > 0
    assert mask.any(), f"{out}: the object covers no pixel"
    assert changed.any(), f"{out}: the composite equals the background"
PY
# A prediction whose panorama is gone: an error naming it, no output.
cp -r pred pred_moved
/usr/bin/python3 -c "import json;p='pred_moved/infer.json';r=json.load(open(p));r['input']='gone.png';json.dump(r,open(p,'w'))"
rc=0
"$phyir" --log-level warn insert pred_moved "$object" "${common[@]}" --out ins_gone > gone.log 2>&1 || rc=$?
[ "$rc" -ne 0 ] && [ "$rc" -lt 128 ] && grep -q "gone.png" gone.log && [ ! -e ins_gone/insert.json ] \
  || die "a prediction without its panorama: exit $rc, $(cat gone.log)"
echo "insert under predicted lighting: OK"

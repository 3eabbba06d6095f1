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
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)  # before the prologue changes directory
source "$here/lib/prologue.sh"
source "$here/lib/tiny_lnet.sh"
view=$(dirname "$(find data -name view.json | head -1)")
[ -d "$view" ] || die "the dataset has no view"
"$phyir" --log-level warn infer --model lnet/checkpoint.pt --input "$view/input.png" --out pred --threads 1
for f in probes.exr probe_mask.exr depth.exr normal.exr basecolor.exr; do
  [ -s "pred/$f" ] || die "phyir infer wrote no $f"
done

# A 1 m cube (scaled to 0.3 m below): visible from every side.
/usr/bin/python3 "$here/lib/cube_gltf.py" cube.gltf
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

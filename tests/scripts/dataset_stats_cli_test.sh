#!/usr/bin/env bash
# `phyir dataset stats DIR --out sheet.png --json stats.json` on a tiny dataset (2 mini rooms
# x 2 views): the summary's sections on stdout, a JSON whose pixel classes partition the
# pixels and whose counts match the manifest, a PNG contact sheet OpenImageIO decodes at the
# expected size, no temporary files left; a folder without manifest fails naming it.
#   $1 = phyir binary, $2 = scratch folder (emptied).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/lib/prologue.sh"

"$phyir" --log-level warn scenes generate --out rooms --count 2 --seed 6 --preset mini
"$phyir" --log-level warn dataset generate --scenes rooms --out data --preset tiny --views-per-scene 2 --threads 2 --quiet
"$phyir" dataset stats --help > help.txt
grep -q -- "--json" help.txt || die "--help does not list --json"

"$phyir" --log-level warn dataset stats data --out sheet.png --json stats.json --thumb-width 128 --quiet > out.txt
cat out.txt
for section in "2 scenes, 4 views" "splits: train" "material mix (4 views, 8192 pixels" "  metal " "  mirror " \
  "light (luminance of color.exr" "input exposure" "render cost (4 of 4 views have a timing.json)" "rays per view"; do
  grep -qF -- "$section" out.txt || die "no '$section' in the summary"
done
/usr/bin/python3 - <<'PY'
import json
import OpenImageIO as oiio
s, m = json.load(open("stats.json")), json.load(open("data/manifest.json"))
f = s["material"]["fractions"]
total = sum(f[k] for k in ["no_geometry", "emissive", "transparent", "mirror", "glossy", "diffuse"])
assert abs(total - 1) < 1e-9, total
assert 0 <= f["metal"] <= f["mirror"] + f["glossy"] + f["diffuse"] + 1e-12
assert s["views"] == len(m["views"]) == 4
assert sum(x["views"] for x in s["splits"].values()) == 4
rays = sum(v["render"]["counters"]["rays_traced"] for v in m["views"]) / 4
assert abs(s["render_cost"]["rays_per_view"]["mean"] - rays) < 1e-6 * rays
p = s["light"]["luminance_percentiles"]
assert p["p1"] <= p["p50"] <= p["p95"] <= p["p99"] <= s["light"]["luminance_max"] * 1.012
sheet = oiio.ImageInput.open("sheet.png")
spec = sheet.spec()
# 4 thumbnails of 128 x 64 in a row: 4 + 4 x (128 + 4) wide, 4 + 64 + 18 + 4 high.
assert (spec.width, spec.height, spec.nchannels) == (532, 90, 3), (spec.width, spec.height, spec.nchannels)
print("stats.json and sheet.png OK")
PY
ls -a | grep -q partial && die "a temporary file was left behind"

mkdir unfinished
if "$phyir" dataset stats unfinished > bad.txt 2>&1; then die "a folder without manifest accepted"; fi
grep -q "unfinished: no manifest.json" bad.txt || { cat bad.txt; die "the error does not name the manifest"; }
echo "dataset_stats_cli_test: OK"

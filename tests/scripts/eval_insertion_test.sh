#!/usr/bin/env bash
# `phyir eval --insertion-views`: insertion scores in eval's report, end to end. A tiny dataset,
# a network trained for a step (its predictions only have to be the toolkit's `phyir infer`
# folders), eval with --model and one view's insertion: metrics.json's "insertion" section has
# every Table 10 sphere under every lighting, finite and non-negative, and report.md its table.
# A scene file that is not the one the view was rendered from, and predictions without probes,
# are refused, naming the file, with no report written.
#   $1 = phyir binary, $2 = scratch folder (emptied).
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)  # before the prologue changes directory
source "$here/lib/prologue.sh"
source "$here/lib/tiny_lnet.sh"
insertion=(--insertion-views 1 --insertion-spp 4 --insertion-truth-spp 8)
common=(--gt data --split train --model lnet/checkpoint.pt --no-relight --no-baselines --quiet --threads 2)
"$phyir" --log-level warn eval "${common[@]}" "${insertion[@]}" --out report > eval.log
/usr/bin/python3 - <<'PY' || die "the insertion section of the report is wrong"
import json, math
m = json.load(open("report/metrics.json"))
ins = m["insertion"]
assert ins["views"] == 1, ins["views"]
assert ins["cases"], "no insertion case (no placement found?)"
for sphere in ("diffuse", "matte_silver", "mirror_silver"):
    for lighting in ("predicted", "gt", "global", "constant"):
        s = ins["mean"][sphere][lighting]
        assert math.isfinite(s["rmse"]) and s["rmse"] >= 0, (sphere, lighting, s)
        assert math.isfinite(s["ssim"]) and -1 <= s["ssim"] <= 1, (sphere, lighting, s)
report = open("report/report.md").read()
assert "## Object insertion" in report and "RMSE predicted" in report, "no insertion table in report.md"
PY
# Predictions without probes (a method that predicts no lighting): insertion refused, naming
# the file, no report.
cp -r report/pred nolight
find nolight -name probes.exr -delete
rc=0
"$phyir" --log-level warn eval --gt data --split train --pred nolight --no-relight --no-baselines --quiet \
  --threads 2 "${insertion[@]}" --out report3 > nolight.log 2>&1 || rc=$?
[ "$rc" -ne 0 ] && [ "$rc" -lt 128 ] && grep -q "probes.exr" nolight.log && [ ! -e report3/metrics.json ] \
  || die "predictions without probes: exit $rc, $(cat nolight.log)"
# The scene changed since the dataset was made: refused, naming the file, no report.
echo " " >> rooms/room_0.gltf
rc=0
"$phyir" --log-level warn eval "${common[@]}" "${insertion[@]}" --out report2 > changed.log 2>&1 || rc=$?
[ "$rc" -ne 0 ] && [ "$rc" -lt 128 ] && grep -q "room_0.gltf" changed.log && grep -q "SHA-256" changed.log \
  && [ ! -e report2/metrics.json ] || die "a changed scene: exit $rc, $(cat changed.log)"
echo "eval insertion: OK"

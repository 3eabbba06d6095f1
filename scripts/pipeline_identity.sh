#!/usr/bin/env bash
# Runs the whole pipeline with two phyir builds and compares what each wrote, byte for byte:
# the check a refactoring commit runs to show the files every stage passes on did not change
# (scripts/bit_identity.sh does the same for single renders). The pipeline is the eval
# regression test's (tests/scripts/eval_regression_test.sh): 6 generated mini rooms, a tiny
# dataset with probes (2 views per scene), `dataset stats`, GMNet then LNet trained for a few
# steps on one thread, `phyir infer` on a test view and `phyir eval --model`. Compared:
#   every file of the dataset (timing.json aside: wall-clock times), the manifest included;
#   the stats report; each training run's log with its timing fields removed; the inference
#   folder; the eval report (metrics.json without timings, report.md).
#
# Usage: scripts/pipeline_identity.sh BEFORE_DIR AFTER_DIR [WORK_DIR]
#   BEFORE_DIR and AFTER_DIR each hold a `phyir` (and its `phyir-torch`). Exits 0 when all is
#   identical, 1 listing what differs, 2 on bad arguments. About a minute on 2 cores (Zen 4).
set -euo pipefail
if [ "${1:-}" = "--help" ] || [ "${1:-}" = "-h" ] || [ $# -lt 2 ]; then
  sed -n '2,14p' "$0" | sed 's/^# \{0,1\}//'
  [ $# -lt 2 ] && [ "${1:-}" != "--help" ] && [ "${1:-}" != "-h" ] && exit 2
  exit 0
fi
before=$(realpath "$1")
after=$(realpath "$2")
work=$(realpath -m "${3:-$(mktemp -d)}")
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
for d in "$before" "$after"; do [ -x "$d/phyir" ] || { echo "pipeline_identity: $d/phyir is not an executable" >&2; exit 2; }; done
export OMP_WAIT_POLICY=passive
source "$root/tests/scripts/pinned_kernels.sh"

run_pipeline() {  # phyir binary, output folder
  local phyir=$1 out=$2
  rm -rf "$out" && mkdir -p "$out" && cd "$out"
  echo "pipeline_identity: $(basename "$out"): scenes, dataset, stats"
  "$phyir" --log-level warn scenes generate --out rooms --count 6 --seed 7 --preset mini
  "$phyir" --log-level warn dataset generate --scenes rooms --out data --preset tiny --views-per-scene 2 \
    --split 0.5,0,0.5 --seed 1 --threads 2 --quiet
  mkdir -p stats && "$phyir" --log-level warn dataset stats data --json stats/stats.json > stats/stats.txt
  echo "pipeline_identity: $(basename "$out"): train, infer, eval"
  local net=(--seed 1 --threads 1 --quiet --input-height 32 --input-width 64 --render-height 16 --render-width 32
             --probe-height 4 --probe-width 8 --diffuse-samples 16 --specular-samples 8 --width-divisor 4)
  "$phyir" --log-level warn train --data data --out gm --stage gmnet --epochs 30 --lr 1e-3 --batch 4 --w-normal 1 "${net[@]}"
  "$phyir" --log-level warn train --data data --out lnet --stage lnet --epochs 10 --lr 1e-3 --batch 4 \
    --init gm/checkpoint.pt --seed 1 --threads 1 --quiet
  local view
  view=$(ls -d data/views/*/v000 | head -1)
  "$phyir" --log-level warn infer --model lnet/checkpoint.pt --input "$view/input.png" --out infer --threads 1 --radiance absolute
  "$phyir" --log-level warn eval --gt data --split test --threads 2 --sphere-size 32 --sphere-spp 16 \
    --relight-positions 2 --figures 2 --quiet --model lnet/checkpoint.pt --out report > eval.txt
  cd - > /dev/null
}

run_pipeline "$before/phyir" "$work/before"
run_pipeline "$after/phyir" "$work/after"

/usr/bin/python3 - "$work/before" "$work/after" <<'PY'
import hashlib, json, os, sys
before, after = sys.argv[1:3]
TIMING = ("seconds", "per_second", "timings", "threads", "timestamp", "date", "time", "host", "duration")

def timeless(value):
    if isinstance(value, dict):
        return {k: timeless(v) for k, v in value.items() if not any(t in k for t in TIMING)}
    if isinstance(value, list):
        return [timeless(v) for v in value]
    return value

def content(path):
    if os.path.basename(path) == "timing.json":
        return None
    data = open(path, "rb").read()
    if path.endswith(".csv"):  # training logs: every column but wall-clock time
        rows = [line.split(",") for line in data.decode().splitlines()]
        keep = [i for i, name in enumerate(rows[0]) if not any(t in name for t in TIMING)] if rows else []
        return [[row[i] for i in keep if i < len(row)] for row in rows]
    if path.endswith((".json", ".jsonl")) and ("/gm/" in path or "/lnet/" in path or "/report/" in path
                                               or "/stats/" in path or "/infer/" in path):
        lines = data.decode().splitlines() if path.endswith(".jsonl") else [data.decode()]
        return [timeless(json.loads(l)) for l in lines if l.strip()]
    return hashlib.sha256(data).hexdigest()

def files(top):
    out = {}
    for d, _, names in os.walk(top):
        for n in names:
            p = os.path.join(d, n)
            if p.endswith((".pt", ".txt", ".log")):  # checkpoints hold torch's own bytes; console text holds times
                continue
            out[os.path.relpath(p, top)] = content(p)
    return out

a, b = files(before), files(after)
differ = sorted(k for k in set(a) | set(b) if a.get(k) != b.get(k))
for k in differ:
    print(f"pipeline_identity: differs: {k}" + ("" if k in a and k in b else " (only in one)"))
print(f"pipeline_identity: {len(a)} files compared, {len(differ)} differ")
sys.exit(1 if differ else 0)
PY

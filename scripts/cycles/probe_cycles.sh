#!/usr/bin/env bash
# One light probe as its own Blender Cycles render: the per-probe cost that `phyir render
# --probes` is compared against (docs/probes-accuracy.md, "Against one render per probe").
#
#   scripts/cycles/probe_cycles.sh --scene ROOM.gltf --subset SUBSET.json [--probes 4]
#       [--res 16x32] [--samples 16,64,256,1024,4096] [--reference-samples 16384]
#       [--threads 2] [--runs /tmp/phyir-probe-cycles] [--csv docs/figures/probes_cycles.csv]
#
# SUBSET.json is written by `phyir bench probes` (subset_*.json: the probes its error is
# measured on, with their origins). For --probes of them, evenly spread, Cycles renders an
# equirectangular h x w panorama at the probe's origin (scripts/cycles/render_cycles.py:
# world-aligned like ours, box filter, no denoising or adaptive sampling, unbiased
# settings, our BRDF's terms with --materials ue4) at each sample count and once at
# --reference-samples; the error of each is its relative RMSE against that converged Cycles
# probe (pooled over the probes, the metric of `phyir bench probes`), and its time is
# Cycles' own render time (`render_seconds`: Blender start-up, scene import, BVH build and
# kernel loading excluded; the CPU seconds of the whole render call are listed too, since
# on a shared machine wall time includes waiting). Every render is skipped if its output
# exists (resumable).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
BLENDER="${BLENDER:-blender}"
PYTHON=/usr/bin/python3   # Debian's, with numpy and OpenImageIO

scene="" subset="" probes=4 res=16x32 samples=16,64,256,1024,4096 reference_samples=16384 threads=2
runs=/tmp/phyir-probe-cycles csv="$ROOT/docs/figures/probes_cycles.csv"
while [[ $# -gt 0 ]]; do
  case "$1" in
    --scene) scene="$2" ;;
    --subset) subset="$2" ;;
    --probes) probes="$2" ;;
    --res) res="$2" ;;
    --samples) samples="$2" ;;
    --reference-samples) reference_samples="$2" ;;
    --threads) threads="$2" ;;
    --runs) runs="$2" ;;
    --csv) csv="$2" ;;
    -h|--help) sed -n '2,19p' "$0"; exit 0 ;;
    *) echo "probe_cycles.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift 2
done
[[ -f "$scene" ]] || { echo "probe_cycles.sh: --scene '$scene' not found" >&2; exit 1; }
[[ -f "$subset" ]] || { echo "probe_cycles.sh: --subset '$subset' not found (run phyir bench probes first)" >&2; exit 1; }
command -v "$BLENDER" >/dev/null || { echo "probe_cycles.sh: '$BLENDER' not found (apt-get install blender)" >&2; exit 1; }
h=${res%x*}
w=${res#*x}
mkdir -p "$runs" "$(dirname "$csv")"
log() { echo "[probe_cycles.sh $(date +%H:%M:%S)] $*" >&2; }

origins=$("$PYTHON" -c "
import json, sys
probes, n = json.load(open(sys.argv[1])), int(sys.argv[2])
for p in probes[::max(1, len(probes) // n)][:n]:  # spread over the subset (it is sorted by index)
    print('{},{:.6f},{:.6f},{:.6f}'.format(p['index'], *p['origin']))
" "$subset" "$probes")

IFS=, read -r -a sample_list <<<"$samples"
for line in $origins; do
  IFS=, read -r index x y z <<<"$line"
  for n in "${sample_list[@]}" "$reference_samples"; do
    out="$runs/probe${index}_${n}spp.exr"
    [[ -f "$out" && -f "${out%.exr}.json" ]] && continue
    log "probe $index at ($x, $y, $z): $n samples"
    "$BLENDER" -b --factory-startup -noaudio -t "$threads" --python "$ROOT/scripts/cycles/render_cycles.py" -- \
      --gltf "$scene" --out "$out" --width "$w" --height "$h" --samples "$n" --seed 1 "--camera=$x,$y,$z" \
      --bounces 7 --threads "$threads" --materials ue4 >"${out%.exr}.log" 2>&1 ||
      { echo "probe_cycles.sh: Cycles failed, see ${out%.exr}.log" >&2; exit 1; }
  done
done

"$PYTHON" - "$runs" "$csv" "$reference_samples" "$samples" <<'PY'
import glob, json, os, re, sys
import numpy as np
import OpenImageIO as oiio
runs, csv_path, ref_n, samples = sys.argv[1], sys.argv[2], int(sys.argv[3]), [int(s) for s in sys.argv[4].split(",")]
def read(path):
    return np.asarray(oiio.ImageBuf(path).get_pixels(oiio.FLOAT))[..., :3].astype(np.float64)
indices = sorted({int(re.match(r"probe(\d+)_", os.path.basename(p)).group(1)) for p in glob.glob(f"{runs}/probe*_{ref_n}spp.exr")})
rows = ["samples,probes,mean_render_seconds_per_probe,mean_render_call_cpu_seconds_per_probe,relative_rmse"]
for n in samples:
    sq, ref_abs, count, seconds, cpu = 0.0, 0.0, 0, [], []
    for k in indices:
        ref = read(f"{runs}/probe{k}_{ref_n}spp.exr")
        img = read(f"{runs}/probe{k}_{n}spp.exr")
        sq += ((img - ref) ** 2).sum()
        ref_abs += np.abs(ref).sum()
        count += ref.size
        timings = json.load(open(f"{runs}/probe{k}_{n}spp.json"))["timings"]
        seconds.append(timings["render_seconds"])
        cpu.append(timings["render_call_cpu_seconds"])
    rel = np.sqrt(sq / count) / (ref_abs / count)
    rows.append(f"{n},{len(indices)},{np.mean(seconds):.4f},{np.mean(cpu):.4f},{rel:.5f}")
    print(f"Cycles {n:6d} samples: {np.mean(seconds):8.3f} s per probe (render only; {np.mean(cpu):.3f} CPU s "
          f"for the render call), relative RMSE {rel:.4f}")
with open(csv_path, "w") as f:
    f.write("\n".join(rows) + "\n")
print(f"wrote {csv_path}")
PY

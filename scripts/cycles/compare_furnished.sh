#!/usr/bin/env bash
# Time to equal error: phyir against Blender Cycles (CPU) on a scene of the benchmark suite
# (a furnished apartment), equirect panoramas, each renderer against its own converged
# reference made of two half references of different seeds (their difference measures the
# reference's own noise). Method: docs/cycles-comparison.md; results:
# docs/cycles-comparison-results.md, "Furnished apartment at night". Steps and layout as compare.sh; errors and figures by compare.py.
#
#   nice -n 10 scripts/cycles/compare_furnished.sh [--suite-scene apartment_night_living]
#       [--suite /work/scratch/suite/suite.json] [--scene GLTF] [--camera X,Y,Z]
#       [--runs /work/scratch/cycles_furnished/apartment_night] [--name apartment_night]
#       [--spp-list 4,8,16,32,64,128,256,512,1024] [--repeats 1] [--reference-spp 4096]
#       [--cycles-reference-spp 2048] [--width 256] [--height 128] [--threads 2]
#       [--targets 0.5,0.3,0.2,0.1] [--figures docs/figures] [--phyir-label LABEL] [--report-only]
#
# The camera: the suite entry's `camera` if it has one, else the one `phyir render` picks
# itself (read back from its render.json), given to Cycles at the same position.
# Each reference is two renders of half the spp (seeds 1000 and 1001), averaged. Every render
# is skipped when its output exists, so an interrupted run resumes and a second run only
# renders what is missing. Cycles runs with the UE4 terms (render_cycles.py --materials ue4).
# A newer phyir: `PHYIR=/path/to/phyir ... --phyir-label L --name NAME_L` renders only
# phyir's sweep, into RUNS/sweep_L, and reuses both references and Cycles' sweep.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
PHYIR="${PHYIR:-$ROOT/build/cli/phyir}"
BLENDER="${BLENDER:-blender}"
PYTHON=/usr/bin/python3   # Debian's, with numpy, matplotlib and OpenImageIO

suite=/work/scratch/suite/suite.json suite_scene=apartment_night_living scene="" camera=""
runs="" name="" spp_list=4,8,16,32,64,128,256,512,1024 repeats=1 reference_spp=4096
cycles_reference_spp=2048 width=256 height=128 threads=2 targets=0.5,0.3,0.2,0.1
figures="$ROOT/docs/figures" phyir_label="" report_only=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --suite) suite="$2" ;;
    --suite-scene) suite_scene="$2" ;;
    --scene) scene="$2" ;;
    --camera) camera="$2" ;;
    --runs) runs="$2" ;;
    --name) name="$2" ;;
    --spp-list) spp_list="$2" ;;
    --repeats) repeats="$2" ;;
    --reference-spp) reference_spp="$2" ;;
    --cycles-reference-spp) cycles_reference_spp="$2" ;;
    --width) width="$2" ;;
    --height) height="$2" ;;
    --threads) threads="$2" ;;
    --targets) targets="$2" ;;
    --figures) figures="$2" ;;
    --phyir-label) phyir_label="$2" ;;
    --report-only) report_only=1; shift; continue ;;
    -h|--help) sed -n '2,22p' "$0"; exit 0 ;;
    *) echo "compare_furnished.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift 2
done
if [[ -z "$scene" ]]; then  # from the suite: its path (relative to suite.json) and camera
  read -r scene suite_camera < <("$PYTHON" - "$suite" "$suite_scene" <<'EOF'
import json, os, sys
suite, wanted = sys.argv[1], sys.argv[2]
for entry in json.load(open(suite))["scenes"]:
    if entry["name"] == wanted:
        camera = ",".join(f"{v:g}" for v in entry["camera"]) if "camera" in entry else ""
        print(os.path.join(os.path.dirname(os.path.abspath(suite)), entry["scene"]), camera)
        break
else:
    sys.exit(f"{suite}: no scene named '{wanted}'")
EOF
)
  camera="${camera:-$suite_camera}"
fi
name="${name:-${suite_scene%_living}}"
runs="${runs:-/work/scratch/cycles_furnished/${suite_scene%_living}}"
sweep="sweep${phyir_label:+_$phyir_label}"
machine="machine${phyir_label:+_$phyir_label}.txt"
[[ -f "$scene" ]] || { echo "compare_furnished.sh: scene '$scene' not found" >&2; exit 1; }
IFS=, read -r -a spps <<<"$spp_list"
mkdir -p "$runs"/{align,reference,sweep,"$sweep"} "$figures"
log() { echo "[compare_furnished.sh $(date +%H:%M:%S)] $*" >&2; }
source "$ROOT/scripts/cycles/common.sh"
reference_spps="ours=$reference_spp,cycles_ue4=$cycles_reference_spp"

analyse() {
  "$PYTHON" "$ROOT/scripts/cycles/compare.py" analyse --runs "$runs" --figures "$figures" --name "$name" \
    --spp-list "$spp_list" --repeats "$repeats" --modes ue4 --reference-spp "$reference_spps" \
    --targets "$targets" --phyir-sweep "$sweep" --machine "$machine" --title "$suite_scene"
}
if ((report_only)); then analyse; exit 0; fi
[[ -x "$PHYIR" ]] || { echo "compare_furnished.sh: $PHYIR is not built" >&2; exit 1; }
command -v "$BLENDER" >/dev/null || { echo "compare_furnished.sh: '$BLENDER' not found (apt-get install blender)" >&2; exit 1; }

# 1. Alignment and camera: phyir with its AOVs from the camera it picks itself (unless one is
#    given), then Cycles with its depth pass from the same position.
if [[ -z "$camera" ]]; then
  if [[ ! -f "$runs/align/ours/render.json" ]]; then
    timed "$runs/align/ours.time.json" "$PHYIR" render "$scene" --out "$runs/align/ours" --width "$width" \
      --height "$height" --spp 16 --seed 7 --max-bounces "$ours_bounces" --threads "$threads" --quiet >/dev/null
  fi
  camera="$("$PYTHON" -c 'import json, sys; print(",".join(f"{v:.6g}" for v in json.load(open(sys.argv[1]))["camera"]["position"]))' \
    "$runs/align/ours/render.json")"
fi
render_ours "$runs/align/ours" 16 7
log "scene $scene, camera at $camera, ${width}x${height}, runs in $runs"
write_machine "$runs/$machine" <<<"scene: $scene; camera $camera
spp: $spp_list; references: phyir $reference_spp spp, Cycles (ue4) $cycles_reference_spp spp, each two halves; repeats $repeats"
render_cycles "$runs/align/cycles.exr" 16 7 ue4 --depth-pass

# 2. Converged references: two halves of different seeds each, averaged.
for h in a b; do
  [[ "$h" == a ]] && seed=1000 || seed=1001
  log "phyir reference half $h, $((reference_spp / 2)) spp"
  render_ours "$runs/reference/ours_$h" $((reference_spp / 2)) "$seed" --no-aovs
  [[ -f "$runs/reference/ours_$h.exr" ]] || cp "$runs/reference/ours_$h/color.exr" "$runs/reference/ours_$h.exr"
  log "Cycles reference half $h, $((cycles_reference_spp / 2)) spp"
  render_cycles "$runs/reference/cycles_ue4_$h.exr" $((cycles_reference_spp / 2)) "$seed" ue4
done
for key in ours cycles_ue4; do
  [[ -f "$runs/reference/$key.exr" ]] || "$PYTHON" "$ROOT/scripts/cycles/compare.py" average \
    "$runs/reference/$key.exr" "$runs/reference/${key}_a.exr" "$runs/reference/${key}_b.exr"
done

# 3. The sweep, one seed per repeat; the renderers alternate at every spp.
for ((r = 1; r <= repeats; ++r)); do
  for spp in "${spps[@]}"; do
    log "repeat $r/$repeats, $spp spp (load $(cut -d' ' -f1 /proc/loadavg))"
    render_ours "$runs/$sweep/ours_spp${spp}_r$r" "$spp" "$r" --no-aovs
    render_cycles "$runs/sweep/cycles_ue4_spp${spp}_r$r.exr" "$spp" "$r" ue4
  done
done
echo "load average at end: $(cut -d' ' -f1-3 /proc/loadavg)" >>"$runs/$machine"

# 4. Errors, time to equal error, CSV and figures.
analyse

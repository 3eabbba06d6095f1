#!/usr/bin/env bash
# Time to equal error: phyir against Blender Cycles (CPU) on one generated glTF room,
# equirectangular panoramas, against shared and per-renderer converged references.
# Method and results: docs/cycles-comparison.md.
#
#   scripts/cycles/compare.sh [--preset mini] [--scene-seed 1] [--width 256] [--height 128]
#       [--spp-list 1,2,4,8,16,32,64,128,256,512] [--reference-spp 4096] [--cycles-reference-spp 4096[,4096]]
#       [--repeats 3] [--threads 2] [--modes principled,ue4] [--reference EXR] [--targets 0.5,0.3,0.2,0.1]
#       [--runs /tmp/phyir-cycles/mini] [--figures docs/figures] [--name mini]
#
# --cycles-reference-spp takes one value per Cycles mode (the last one repeats).
# Every step skips outputs that already exist, so an interrupted run resumes; delete the
# runs folder to start over. --reference reuses a converged phyir image of the same scene,
# camera and size (e.g. the reference.exr of `phyir bench convergence`).
# Cycles modes: `principled` renders the importer's Principled BSDF as is; `ue4` rebuilds it
# from the terms of our BRDF (scripts/cycles/render_cycles.py) to separate material-model
# bias from light-transport bias.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
PHYIR="${PHYIR:-$ROOT/build/cli/phyir}"
BLENDER="${BLENDER:-blender}"
PYTHON=/usr/bin/python3   # Debian's, with numpy, matplotlib and OpenImageIO

preset=mini scene_seed=1 width=256 height=128
spp_list=1,2,4,8,16,32,64,128,256,512 reference_spp=4096 cycles_reference_spp=4096
repeats=3 threads=2 modes=principled,ue4 reference="" targets=0.5,0.3,0.2,0.1 runs="" figures="$ROOT/docs/figures" name=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --preset) preset="$2" ;;
    --scene-seed) scene_seed="$2" ;;
    --width) width="$2" ;;
    --height) height="$2" ;;
    --spp-list) spp_list="$2" ;;
    --reference-spp) reference_spp="$2" ;;
    --cycles-reference-spp) cycles_reference_spp="$2" ;;
    --repeats) repeats="$2" ;;
    --threads) threads="$2" ;;
    --modes) modes="$2" ;;
    --reference) reference="$2" ;;
    --targets) targets="$2" ;;
    --runs) runs="$2" ;;
    --figures) figures="$2" ;;
    --name) name="$2" ;;
    -h|--help) sed -n '2,17p' "$0"; exit 0 ;;
    *) echo "compare.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift 2
done
name="${name:-$preset}"
runs="${runs:-/tmp/phyir-cycles/$name}"
[[ -x "$PHYIR" ]] || { echo "compare.sh: $PHYIR is not built" >&2; exit 1; }
command -v "$BLENDER" >/dev/null || { echo "compare.sh: '$BLENDER' not found (apt-get install blender)" >&2; exit 1; }
IFS=, read -r -a spps <<<"$spp_list"
IFS=, read -r -a cycles_modes <<<"$modes"
IFS=, read -r -a cycles_reference_spps <<<"$cycles_reference_spp"
cycles_spp_of() {  # MODE-INDEX
  local n=${#cycles_reference_spps[@]}
  echo "${cycles_reference_spps[$(($1 < n ? $1 : n - 1))]}"
}
mkdir -p "$runs"/{scene,align,reference,sweep} "$figures"
log() { echo "[compare.sh $(date +%H:%M:%S)] $*" >&2; }

source "$ROOT/scripts/cycles/common.sh"

# 1. The scene: one generated room.
if ! ls "$runs"/scene/room_*.gltf >/dev/null 2>&1; then
  "$PHYIR" scenes generate --out "$runs/scene" --count 1 --seed "$scene_seed" --preset "$preset" >/dev/null
fi
scene="$(ls "$runs"/scene/room_*.gltf | head -1)"
# The camera: world position of the glTF camera node (panoramas ignore its rotation).
camera="$("$PYTHON" "$ROOT/scripts/cycles/compare.py" camera "$scene")"
log "scene $scene, camera at $camera, ${width}x${height}"

write_machine "$runs/machine.txt" <<<"spp: $spp_list; references: phyir $reference_spp spp, Cycles ($modes) $cycles_reference_spp spp; repeats $repeats"

# 2. Alignment: our AOVs and a Cycles render with its depth pass.
render_ours "$runs/align/ours" 16 7
render_cycles "$runs/align/cycles.exr" 16 7 principled --depth-pass

# 3. Converged references.
reference_spps="ours=$reference_spp"
for i in "${!cycles_modes[@]}"; do
  mode="${cycles_modes[$i]}" spp="$(cycles_spp_of "$i")"
  log "Cycles ($mode) reference, $spp spp"
  render_cycles "$runs/reference/cycles_$mode.exr" "$spp" 1000 "$mode"
  reference_spps+=",cycles_$mode=$spp"
done
if [[ ! -f "$runs/reference/ours.exr" ]]; then
  if [[ -n "$reference" ]]; then
    cp "$reference" "$runs/reference/ours.exr"
    echo "reused $reference" >"$runs/reference/ours.txt"
  else
    log "phyir reference, $reference_spp spp"
    render_ours "$runs/reference/ours" "$reference_spp" 1000 --no-aovs
    cp "$runs/reference/ours/color.exr" "$runs/reference/ours.exr"
  fi
fi

# 4. The sweep: renderers alternate at every spp; each repeat uses its own seed. Times are
#    the minimum over repeats, errors the mean (compare.py).
for ((r = 1; r <= repeats; ++r)); do
  for spp in "${spps[@]}"; do
    log "repeat $r/$repeats, $spp spp"
    render_ours "$runs/sweep/ours_spp${spp}_r$r" "$spp" "$r" --no-aovs
    for mode in "${cycles_modes[@]}"; do
      render_cycles "$runs/sweep/cycles_${mode}_spp${spp}_r$r.exr" "$spp" "$r" "$mode"
    done
  done
done
echo "load average at end: $(cut -d' ' -f1-3 /proc/loadavg)" >>"$runs/machine.txt"

# 5. Errors, time to equal error, CSV and figures.
"$PYTHON" "$ROOT/scripts/cycles/compare.py" analyse --runs "$runs" --figures "$figures" --name "$name" \
  --spp-list "$spp_list" --repeats "$repeats" --modes "$modes" --reference-spp "$reference_spps" \
  --targets "$targets"

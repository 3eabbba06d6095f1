#!/usr/bin/env bash
# The Blender-exported lit room (tests/data/gltf/blender_lit_room, KHR_lights_punctual point,
# spot and sun) rendered by phyir and by Cycles from the same point as equirect panoramas,
# two seeds each, then compared by mean radiance and block z-scores (lit_room_agreement.py).
# Method and results: docs/cycles-comparison-blender-exports.md, "Lit room exported by Blender".
#
#   scripts/cycles/compare_lit_room.sh [--runs /tmp/phyir-cycles/lit_room] [--seeds 1,2]
#       [--variants lit_room,no_spot,spot_only,no_spot_direct,spot_only_direct]
#       [--spp-full 2048] [--spp-variants 1024] [--spp-direct 256] [--width 256] [--height 128]
#       [--threads 2] [--block 8] [--figures docs/figures] [--name cycles_lit_room] [--report-only]
#       [--supersample K]
#
# Variants: lit_room (the file as exported, --spp-full), no_spot and spot_only (the same file
# with lights' node references dropped, written into RUNS/scenes; --spp-variants), and the
# two *_direct ones (direct light only: phyir --max-bounces 1 = Cycles max_bounces 0;
# --spp-direct). Full transport: phyir --max-bounces 8 = Cycles max_bounces 7, Cycles with
# the UE4 terms (render_cycles.py --materials ue4), lamp radii and sun angle set to 0.
# Outputs: RUNS/phyir/<variant>_s<seed>/ (color.exr, depth.exr, render.json) and
# RUNS/cycles/<variant>_s<seed>.exr (+ .json, .log); each is skipped if it exists (a render
# made elsewhere can be linked in), so an interrupted run resumes. One render at a time;
# run it under `nice` on a shared machine. PHYIR and BLENDER override the binaries.
# --supersample K renders phyir at K x the size with spp / K^2 and box-filters it back (texture
# footprints K x smaller). PHYIR=build-cycles-terms/cli/phyir (cmake -DPHYIR_BRDF_CYCLES_TERMS=ON)
# renders with Cycles' specular terms: docs/cycles-comparison-blender-exports.md, "With Cycles' specular terms".
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
PHYIR="${PHYIR:-$ROOT/build/cli/phyir}"
BLENDER="${BLENDER:-blender}"
PYTHON=/usr/bin/python3   # Debian's, with numpy, matplotlib and OpenImageIO

runs=/tmp/phyir-cycles/lit_room seeds=1,2 variants=lit_room,no_spot,spot_only,no_spot_direct,spot_only_direct
spp_full=2048 spp_variants=1024 spp_direct=256 width=256 height=128 threads=2 block=8
figures="$ROOT/docs/figures" name=cycles_lit_room report_only=0 supersample=1
while [[ $# -gt 0 ]]; do
  case "$1" in
    --runs) runs="$2" ;;
    --seeds) seeds="$2" ;;
    --variants) variants="$2" ;;
    --spp-full) spp_full="$2" ;;
    --spp-variants) spp_variants="$2" ;;
    --spp-direct) spp_direct="$2" ;;
    --width) width="$2" ;;
    --height) height="$2" ;;
    --threads) threads="$2" ;;
    --block) block="$2" ;;
    --figures) figures="$2" ;;
    --name) name="$2" ;;
    --supersample) supersample="$2" ;;
    --report-only) report_only=1; shift; continue ;;
    -h|--help) sed -n '2,24p' "$0"; exit 0 ;;
    *) echo "compare_lit_room.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift 2
done
IFS=, read -r -a seed_list <<<"$seeds"
IFS=, read -r -a variant_list <<<"$variants"
room="$ROOT/tests/data/gltf/blender_lit_room/lit_room.gltf"
camera=-1.2,1.5,1.2   # the glTF camera node's position (README.md of the room)
log() { echo "[compare_lit_room.sh $(date +%H:%M:%S)] $*" >&2; }

timed() {  # OUT.json COMMAND...: wall and CPU seconds of the whole process
  local out="$1"; shift
  /usr/bin/time -f '{"wall_seconds": %e, "user_seconds": %U, "system_seconds": %S}' -o "$out" "$@"
}

scene_of() {  # VARIANT -> glTF path
  case "${1%_direct}" in
    lit_room) echo "$room" ;;
    no_spot|spot_only) echo "$runs/scenes/${1%_direct}.gltf" ;;
    *) echo "compare_lit_room.sh: unknown variant '$1'" >&2; exit 2 ;;
  esac
}
spp_of() {  # VARIANT
  case "$1" in
    lit_room) echo "$spp_full" ;;
    *_direct) echo "$spp_direct" ;;
    *) echo "$spp_variants" ;;
  esac
}
ours_bounces_of() { [[ "$1" == *_direct ]] && echo 1 || echo 8; }   # Cycles: ours minus one

render_ours() {  # VARIANT SEED
  local variant="$1" seed="$2" dir="$runs/phyir/$1_s$2"
  [[ -f "$dir/render.json" ]] && return 0
  # --supersample K: K x the size at spp / K^2 (the same samples per output pixel), so each
  # camera hit's texture footprint is K x smaller; box-filtered back to the output size.
  local k=$supersample spp=$(( ($(spp_of "$variant") + supersample * supersample - 1) / (supersample * supersample) ))
  local out="$dir"; [[ $k -gt 1 ]] && out="$dir/supersampled"
  log "phyir $variant seed $seed, $spp spp at ${k}x (load $(cut -d' ' -f1 /proc/loadavg))"
  timed "$dir.time.json" "$PHYIR" --log-level warn render "$(scene_of "$variant")" --out "$out" \
    --camera="$camera" --width $((width * k)) --height $((height * k)) --spp "$spp" \
    --max-bounces "$(ours_bounces_of "$variant")" --seed "$seed" --threads "$threads" --quiet >"$dir.log" 2>&1 ||
    { echo "compare_lit_room.sh: phyir failed, see $dir.log" >&2; tail -20 "$dir.log" >&2; exit 1; }
  [[ $k -gt 1 ]] && "$PYTHON" "$ROOT/scripts/cycles/lit_room_agreement.py" downsample --dir "$dir" --factor "$k"
  return 0
}

render_cycles() {  # VARIANT SEED
  local variant="$1" seed="$2" out="$runs/cycles/$1_s$2.exr"
  [[ -f "$out" && -f "${out%.exr}.json" ]] && return 0
  log "Cycles $variant seed $seed, $(spp_of "$variant") spp (load $(cut -d' ' -f1 /proc/loadavg))"
  timed "${out%.exr}.time.json" "$BLENDER" -b --factory-startup -noaudio -t "$threads" --python-exit-code 1 \
    --python "$ROOT/scripts/cycles/render_cycles.py" -- --gltf "$(scene_of "$variant")" --out "$out" \
    --width "$width" --height "$height" --samples "$(spp_of "$variant")" --seed "$seed" \
    --bounces $(($(ours_bounces_of "$variant") - 1)) --camera="$camera" --threads "$threads" \
    --materials ue4 >"${out%.exr}.log" 2>&1 ||
    { echo "compare_lit_room.sh: Cycles failed, see ${out%.exr}.log" >&2; tail -20 "${out%.exr}.log" >&2; exit 1; }
}

if [[ $report_only == 0 ]]; then
  [[ -x "$PHYIR" ]] || { echo "compare_lit_room.sh: $PHYIR is not built (or set PHYIR)" >&2; exit 1; }
  command -v "$BLENDER" >/dev/null || { echo "compare_lit_room.sh: '$BLENDER' not found (apt-get install blender)" >&2; exit 1; }
  mkdir -p "$runs"/{scenes,phyir,cycles}
  "$PYTHON" "$ROOT/scripts/cycles/lit_room_agreement.py" variants --gltf "$room" --out "$runs/scenes" >/dev/null
  {
    echo "date: $(date -Iseconds)"
    echo "cpu: $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2- | sed 's/^ //'), $(nproc) cores"
    echo "load average at start: $(cut -d' ' -f1-3 /proc/loadavg)"
    echo "phyir: $PHYIR ($("$PHYIR" --version 2>/dev/null | head -1), md5 $(md5sum "$PHYIR" | cut -c1-12)); scripts from $(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
    echo "blender: $("$BLENDER" --version 2>/dev/null | head -1)"
    echo "variants: $variants; seeds $seeds; spp full $spp_full, variants $spp_variants, direct $spp_direct; threads $threads"
  } >>"$runs/machine.txt"
  for variant in "${variant_list[@]}"; do
    for seed in "${seed_list[@]}"; do
      render_ours "$variant" "$seed"
      render_cycles "$variant" "$seed"
    done
  done
  echo "load average at end: $(cut -d' ' -f1-3 /proc/loadavg) ($(date -Iseconds))" >>"$runs/machine.txt"
fi

"$PYTHON" "$ROOT/scripts/cycles/lit_room_agreement.py" report --runs "$runs" --variants "$variants" \
  --seeds "$seeds" --block "$block" --figures "$figures" --name "$name"

#!/usr/bin/env bash
# The Blender-exported room lit through blended lamp glass (tests/data/gltf/blender_glass_lamp,
# made by scripts/blender/make_glass_lamp_room.py: alphaMode BLEND globe, lampshade and
# diffuser; two point lights and an emissive bulb) rendered by phyir and by Cycles from the
# same point as equirect panoramas, two seeds each, compared by mean radiance and 8 x 8 block
# z-scores with lit_room_agreement.py's statistics (docs/cycles-comparison-blender-exports.md, "Lit room
# exported by Blender", Method), broken down by the first surface hit.
#
#   scripts/cycles/compare_glass_lamp.sh [--runs /tmp/phyir-cycles/glass_lamp] [--seeds 1,2]
#       [--variants glass_lamp,glass_lamp_direct] [--modes ue4] [--spp 1024] [--spp-direct 256]
#       [--width 256] [--height 128] [--threads 2] [--block 8]
#       [--figure docs/figures/cycles_glass_lamp.png] [--report-only]
#
# Variants: glass_lamp (the file as exported), table_lamp, pendant (one point light, the bulb's
# emission removed), sconce (the emissive bulb only) and no_glass (the globe, lampshade and
# diffuser removed: the materials and lights without alpha), written into RUNS/scenes; a _direct
# suffix renders direct light only (phyir --max-bounces 1 = Cycles max_bounces 0, --spp-direct).
# Full transport: phyir --max-bounces 8 = Cycles max_bounces 7. Cycles --materials MODE for
# each of --modes: ue4 (our BRDF's terms, mixed with a Transparent BSDF by the Principled Alpha
# input as the importer's material is) or principled (the importer's material as is). RENDER_CYCLES overrides the Cycles script, PHYIR and BLENDER
# the binaries. Outputs: RUNS/phyir/<variant>_s<seed>/, RUNS/cycles_<mode>/<variant>_s<seed>.exr,
# RUNS/report.json (every number), RUNS/report.png (every variant), FIGURE (glass_lamp per mode).
# Every render is skipped when its output exists. Run it under `nice` on a shared machine.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
PHYIR="${PHYIR:-$ROOT/build/cli/phyir}"
BLENDER="${BLENDER:-blender}"
RENDER_CYCLES="${RENDER_CYCLES:-$ROOT/scripts/cycles/render_cycles.py}"
PYTHON=/usr/bin/python3   # Debian's, with numpy, matplotlib and OpenImageIO
source "$ROOT/scripts/cycles/common.sh"   # timed, render_ours, write_machine

runs=/tmp/phyir-cycles/glass_lamp seeds=1,2 variants=glass_lamp,glass_lamp_direct modes=ue4
spp=1024 spp_direct=256 width=256 height=128 threads=2 block=8
figure="$ROOT/docs/figures/cycles_glass_lamp.png" report_only=0
while [[ $# -gt 0 ]]; do
  case "$1" in
    --runs) runs="$2" ;; --seeds) seeds="$2" ;; --variants) variants="$2" ;; --modes) modes="$2" ;;
    --spp) spp="$2" ;; --spp-direct) spp_direct="$2" ;; --width) width="$2" ;; --height) height="$2" ;;
    --threads) threads="$2" ;; --block) block="$2" ;; --figure) figure="$2" ;;
    --report-only) report_only=1; shift; continue ;;
    -h|--help) sed -n '2,24p' "$0"; exit 0 ;;
    *) echo "compare_glass_lamp.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift 2
done
gltf="$ROOT/tests/data/gltf/blender_glass_lamp/glass_lamp_room.gltf"
camera=-0.2,1.4,0.6   # the glTF camera node's position (make_glass_lamp_room.py prints it)
IFS=, read -r -a seed_list <<<"$seeds"; IFS=, read -r -a variant_list <<<"$variants"; IFS=, read -r -a mode_list <<<"$modes"
log() { echo "[compare_glass_lamp.sh $(date +%H:%M:%S)] $*" >&2; }

render_cycles() {  # OUT.exr SPP SEED MODE: common.sh's, with RENDER_CYCLES
  local out="$1"
  [[ -f "${out%.exr}.json" ]] && return 0
  timed "${out%.exr}.time.json" "$BLENDER" -b --factory-startup -noaudio -t "$threads" --python-exit-code 1 \
    --python "$RENDER_CYCLES" -- --gltf "$scene" --out "$out" --width "$width" --height "$height" --samples "$2" \
    --seed "$3" --bounces "$cycles_bounces" --camera="$camera" --threads "$threads" --materials "$4" >"${out%.exr}.log" 2>&1 ||
    { echo "compare_glass_lamp.sh: Cycles failed, see ${out%.exr}.log" >&2; tail -20 "${out%.exr}.log" >&2; exit 1; }
}

if [[ $report_only == 0 ]]; then
  [[ -x "$PHYIR" ]] || { echo "compare_glass_lamp.sh: $PHYIR is not built (or set PHYIR)" >&2; exit 1; }
  mkdir -p "$runs"/{scenes,phyir} "${mode_list[@]/#/$runs/cycles_}"
  cp "${gltf%.gltf}.bin" "$runs/scenes/"
  "$PYTHON" - "$gltf" "$runs/scenes" <<'EOF'
import json, os, sys  # the variants: lights' node references dropped, emission removed, blended meshes removed
gltf, out = sys.argv[1:]
doc = json.load(open(gltf))
names = [light["name"] for light in doc["extensions"]["KHR_lights_punctual"]["lights"]]
keep = {"glass_lamp": (set(names), True, True), "table_lamp": ({"table_lamp"}, False, True),
        "pendant": ({"pendant_lamp"}, False, True), "sconce": (set(), True, True), "no_glass": (set(names), True, False)}
for variant, (lights, emission, glass) in keep.items():
    d = json.loads(json.dumps(doc))
    for node in d["nodes"]:
        if not glass and "mesh" in node and any(d["materials"][p["material"]].get("alphaMode") == "BLEND"
                                                for p in d["meshes"][node["mesh"]]["primitives"]):
            del node["mesh"]
    for item in d["nodes"] + ([] if emission else d["materials"]):
        ext = item.get("extensions", {})
        if "KHR_lights_punctual" in ext and names[ext["KHR_lights_punctual"]["light"]] not in lights:
            del ext["KHR_lights_punctual"]
        if "emissiveFactor" in item:
            del item["emissiveFactor"]
            ext.pop("KHR_materials_emissive_strength", None)
        if "extensions" in item and not ext:
            del item["extensions"]
    json.dump(d, open(os.path.join(out, variant + ".gltf"), "w"), indent=1)
EOF
  write_machine "$runs/machine.txt" <<<"cycles script: $RENDER_CYCLES (md5 $(md5sum "$RENDER_CYCLES" | cut -c1-12)); variants $variants; modes $modes; seeds $seeds; spp $spp, direct $spp_direct"
  for variant in "${variant_list[@]}"; do
    scene="$runs/scenes/${variant%_direct}.gltf" n=$spp ours_bounces=8
    [[ $variant == *_direct ]] && n=$spp_direct ours_bounces=1
    cycles_bounces=$((ours_bounces - 1))
    for seed in "${seed_list[@]}"; do
      log "phyir $variant seed $seed, $n spp (load $(cut -d' ' -f1 /proc/loadavg))"
      render_ours "$runs/phyir/${variant}_s$seed" "$n" "$seed" --exposure 0
      for mode in "${mode_list[@]}"; do
        log "Cycles ($mode) $variant seed $seed, $n spp (load $(cut -d' ' -f1 /proc/loadavg))"
        render_cycles "$runs/cycles_$mode/${variant}_s$seed.exr" "$n" "$seed" "$mode"
      done
    done
  done
  echo "load average at end: $(cut -d' ' -f1-3 /proc/loadavg) ($(date -Iseconds))" >>"$runs/machine.txt"
fi

# Report: lit_room_agreement.py's per-variant statistics and figure, with its by-surface
# breakdown replaced by this room's (blended surfaces from phyir's mask_transparent AOV).
"$PYTHON" - "$ROOT" "$runs" "$modes" "$variants" "$seeds" "$block" "$figure" "$gltf" <<'EOF'
import json, os, sys
import numpy as np
root, runs, modes, variants, seeds, block, figure, gltf = sys.argv[1:]
sys.path.insert(0, os.path.join(root, "scripts", "cycles"))
import lit_room_agreement as L
from compare import camera_position, node_matrix, read_exr

doc = json.load(open(gltf))
names = [light["name"] for light in doc["extensions"]["KHR_lights_punctual"]["lights"]]
lamp = {names[n["extensions"]["KHR_lights_punctual"]["light"]]: node_matrix(n)[:3, 3]
        for n in doc["nodes"] if "KHR_lights_punctual" in n.get("extensions", {})}

def regions(runs, variant, seed, camera, p_avg, c_avg):
    """phyir / Cycles by first surface: the blended ones, the bulb, the room's inner faces split
    by whether the pendant's light reaches them through its fabric or its openings, furniture."""
    aov = lambda name: read_exr(os.path.join(runs, "phyir", f"{variant}_s{seed}", name + ".exr"), ("Y",))[..., 0]
    depth = aov("depth").astype(np.float64)
    hit = np.isfinite(depth) & (depth > 0) & (depth < 1e3)
    x = np.asarray(camera) + np.where(hit, depth, 0.0)[..., None] * L.pixel_directions(depth.shape[1], depth.shape[0])
    blended, bulb = hit & (aov("mask_transparent") > 0.5), hit & (aov("mask_emissive") > 0.5)
    near = lambda name, r: np.linalg.norm(x - lamp[name], axis=2) < r
    v = x - lamp["pendant_lamp"]  # the shade's openings: radius 0.22 m 0.12 m below the light, 0.11 m 0.12 m above
    with np.errstate(divide="ignore", invalid="ignore"):
        fabric = np.hypot(v[..., 0], v[..., 2]) * 0.12 / np.abs(v[..., 1]) > np.where(v[..., 1] < 0, 0.22, 0.11)
    shell = hit & ~blended & ~bulb & ((np.abs(x[..., 1] - 2.6) < 0.01) | (np.abs(x[..., 1]) < 0.01)
                                      | (np.abs(np.abs(x[..., 0]) - 2.0) < 0.01) | (np.abs(np.abs(x[..., 2]) - 1.5) < 0.01))
    masks = {"globe": blended & near("table_lamp", 0.2), "lampshade": blended & near("pendant_lamp", 0.35),
             "diffuser": blended & ~near("table_lamp", 0.2) & ~near("pendant_lamp", 0.35), "bulb": bulb,
             "room, pendant through fabric": shell & fabric, "room, pendant through openings": shell & ~fabric,
             "furniture": hit & ~blended & ~bulb & ~shell}
    return {k: {"pixels": int(m.sum()), "share_of_cycles": float(c_avg[m].sum() / c_avg.sum()),
                "ratio": float(p_avg[m].sum() / c_avg[m].sum()), "ratio_rgb": (p_avg[m].sum(0) / c_avg[m].sum(0)).tolist()}
            for k, m in masks.items() if m.any() and c_avg[m].sum() > 0}

L.surface_ratios = regions
camera, seeds = camera_position(gltf), [int(s) for s in seeds.split(",")]
results, arrays = [], []
for mode in modes.split(","):
    view = os.path.join(runs, "view_" + mode)  # the layout analyse_variant reads: phyir/, cycles/
    os.makedirs(view, exist_ok=True)
    for name, target in (("phyir", "../phyir"), ("cycles", "../cycles_" + mode)):
        if not os.path.islink(os.path.join(view, name)):
            os.symlink(target, os.path.join(view, name))
    for variant in variants.split(","):
        r, a = L.analyse_variant(view, variant, seeds, int(block), camera, None)
        r.update(variant=f"{variant}, Cycles {mode}", mode=mode)
        results.append(r), arrays.append(a)
        print(f"{r['variant']}: phyir / Cycles {r['ratio_channel_mean']:.4f} +- {r['ratio_standard_error']:.4f} "
              f"{L.fmt(r['ratio'])}; {block}x{block} blocks: rel. RMSE {r['block_relative_rmse']:.4f} (noise "
              f"{r['block_relative_rmse_noise']:.4f}), |z|>3 {100 * r['z_fraction_above_3']:.1f}% (null "
              f"{100 * r['z_null_fraction_above_3']:.1f}%), max |z| {r['z_max_abs']:.2f} at {r['z_max_at_direction']}; "
              f"scaled: |z|>3 {100 * r['z_scaled_fraction_above_3']:.1f}%, max {r['z_scaled_max_abs']:.2f}")
        for k, s in r["by_surface"].items():
            print(f"  {k}: {s['pixels']} px, {100 * s['share_of_cycles']:.1f}% of Cycles' light, ratio {s['ratio']:.4f}")
json.dump({"camera": camera.tolist(), "seeds": seeds, "block": int(block), "variants": results},
          open(os.path.join(runs, "report.json"), "w"), indent=1)
L.figure(results, arrays, os.path.join(runs, "report.png"))
first = variants.split(",")[0]
L.figure(*zip(*[(r, a) for r, a in zip(results, arrays) if r["variant"].startswith(first + ",")]), figure)
print(f"wrote {runs}/report.json, {runs}/report.png, {figure}")
EOF

#!/usr/bin/env bash
# The training recipe of issue 24 item 5 (docs/model-results.md "Training recipe"): furnished apartments,
# a dataset at the model's default resolutions, the four stages for two arms (targets in the
# input's units, the exposure fix; and in absolute radiance, without it), `phyir eval` on the
# test split with its baselines, a results table (Markdown + CSV), the training curves and the
# measured costs. Every step records what it ran in OUT/stamps and is skipped when run again
# with the same settings; an interrupted training stage resumes from its checkpoint.
set -euo pipefail

usage() {
  cat <<'EOF'
Usage: scripts/train_recipe.sh --out DIR [--pilot | --full] [options]

Runs, in DIR (outside the repository; every step skips what is done, so run it again after
an interruption):
  1. phyir scenes generate --preset apartment --count N --seed S        DIR/scenes
  2. phyir dataset generate at the model's default resolutions           DIR/data
     (256x128 panoramas, 32x64 probe grid of 8x16 texels, cheap cache probes)
  3. phyir train: gmnet once (GMNet's losses have no radiance unit), then for each arm
     (input: the exposure fix; absolute: targets in absolute radiance) lnet, joint, gsnet,
     each stage --init from the previous one                                DIR/runs/<arm>/<stage>
  4. phyir eval --model on the test split with the baselines              DIR/eval/<arm>
     and the same predictions scored in input units (--radiance input)     DIR/eval/<arm>_input
  5. DIR/results.md, results.csv (every metric: both arms, both baselines, margins; radiance
     metrics in both units, over all test views and per lighting, day and night),
     costs.csv (wall and CPU seconds of each step, per view and per training step),
     curves/*.png (scripts/plot_training.py)

Sizes (--pilot is the default):
  --pilot                 8 apartments x 5 views, short stages: 1,190 CPU s measured (about
                          10-12 min on 2 dedicated cores; 45 min at load 6-9 on the shared one)
  --full                  40 apartments x 8 views, longer stages: about 4 CPU hours, 2-2.5 h on
                          2 dedicated cores (estimated from the pilot's costs, docs/model-results.md)
  --count N               apartments                       [pilot 8, full 40]
  --views-per-scene K     views per apartment              [pilot 5, full 8]
  --epochs G,L,J,S        epochs of gmnet, lnet, joint, gsnet [pilot 12,6,2,6; full 30,15,3,10]
  --seed S                seed of the apartments           [1]
  --dataset-seed S        first dataset seed tried: the first seed from S whose split of the
                          apartments has a val and a test apartment (and the train share
                          less one) is used [1]
  --split T,V,E           scene fractions                  [0.7,0.15,0.15]

Dataset (defaults chosen for a cheap view; see docs/model-results.md for the measured seconds):
  --width W --height H    panorama [256 x 128]             --spp N [32]
  --probe-grid HxW [32x64]  --probe-res hxw [8x16]  --probe-spp N [2]
  --probe-cache-spp N [16]  --probe-cache-cell M [0.15]  (cache: 11 CPU s a view against 45 s at
                          the defaults 64 and 0.05 m on these apartments)

Training:
  --width-divisor D       GMNet/LNet channel divisor [2]   --lnet-head paper|light [light]
  --arms "A B"            arms to run [input absolute]     --threads T  torch threads [2]
  --val-views N           validation views per pass [8]
  --gmnet-lr LR [1e-3]  --lnet-lr LR [pilot 1e-4 (B.1), full 1e-3: the pilot's LNet barely
                          moved at 1e-4, docs/model-results.md]  --joint-lr LR [1e-5]  --gsnet-lr LR [5e-4]
  --lr-schedule KIND      constant|step|cosine [cosine]
  --gmnet-w-normal X      GMNet's normal weight [1; B.1: 0.1]

Evaluation:
  --no-relight            skip the relighting spheres (Table 5)

Other:
  --phyir BIN             the phyir binary [build/cli/phyir of this repository]
  --dataset-threads T     dataset generation threads [2]
  -h, --help              this text
EOF
}

repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out="" size=pilot phyir="$repo/build/cli/phyir"
count="" views="" epochs="" seed=1 dataset_seed=1 split=0.7,0.15,0.15
width=256 height=128 spp=32 probe_grid=32x64 probe_res=8x16 probe_spp=2 probe_cache_spp=16 probe_cache_cell=0.15
width_divisor=2 lnet_head=light arms="input absolute" threads=2 val_views=8 dataset_threads=2
gmnet_lr=1e-3 lnet_lr="" joint_lr=1e-5 gsnet_lr=5e-4 lr_schedule=cosine gmnet_w_normal=1 relight=1

while [[ $# -gt 0 ]]; do
  case "$1" in
    -h|--help) usage; exit 0 ;;
    --out) out=$2; shift ;;
    --pilot) size=pilot ;;
    --full) size=full ;;
    --count) count=$2; shift ;;
    --views-per-scene) views=$2; shift ;;
    --epochs) epochs=$2; shift ;;
    --seed) seed=$2; shift ;;
    --dataset-seed) dataset_seed=$2; shift ;;
    --split) split=$2; shift ;;
    --width) width=$2; shift ;;
    --height) height=$2; shift ;;
    --spp) spp=$2; shift ;;
    --probe-grid) probe_grid=$2; shift ;;
    --probe-res) probe_res=$2; shift ;;
    --probe-spp) probe_spp=$2; shift ;;
    --probe-cache-spp) probe_cache_spp=$2; shift ;;
    --probe-cache-cell) probe_cache_cell=$2; shift ;;
    --width-divisor) width_divisor=$2; shift ;;
    --lnet-head) lnet_head=$2; shift ;;
    --arms) arms=$2; shift ;;
    --threads) threads=$2; shift ;;
    --val-views) val_views=$2; shift ;;
    --gmnet-lr) gmnet_lr=$2; shift ;;
    --lnet-lr) lnet_lr=$2; shift ;;
    --joint-lr) joint_lr=$2; shift ;;
    --gsnet-lr) gsnet_lr=$2; shift ;;
    --lr-schedule) lr_schedule=$2; shift ;;
    --gmnet-w-normal) gmnet_w_normal=$2; shift ;;
    --no-relight) relight=0 ;;
    --phyir) phyir=$2; shift ;;
    --dataset-threads) dataset_threads=$2; shift ;;
    *) echo "train_recipe.sh: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done

[[ -n "$out" ]] || { echo "train_recipe.sh: --out DIR is required (see --help)" >&2; exit 2; }
[[ -x "$phyir" ]] || { echo "train_recipe.sh: $phyir is not an executable phyir (build it, or pass --phyir)" >&2; exit 2; }
if [[ $size == pilot ]]; then
  : "${count:=8}" "${views:=5}" "${epochs:=12,6,2,6}" "${lnet_lr:=1e-4}"
else
  : "${count:=40}" "${views:=8}" "${epochs:=30,15,3,10}" "${lnet_lr:=1e-3}"
fi
IFS=, read -r ep_gm ep_l ep_j ep_gs <<<"$epochs"
[[ -n "$ep_gs" ]] || { echo "train_recipe.sh: --epochs wants four numbers G,L,J,S, got '$epochs'" >&2; exit 2; }
for arm in $arms; do
  [[ $arm == input || $arm == absolute ]] || { echo "train_recipe.sh: arm '$arm': input or absolute" >&2; exit 2; }
done

out=$(realpath -m "$out")
case "$out/" in "$repo"/*) echo "train_recipe.sh: --out $out is inside the repository; use a scratch folder" >&2; exit 2 ;; esac
mkdir -p "$out"
mkdir -p "$out/stamps" "$out/costs" "$out/logs" "$out/curves"
export OMP_WAIT_POLICY=passive  # spinning OpenMP threads are 5-8x slower on a shared machine (docs/model.md)
log() { echo "[$(date -u +%H:%M:%S)] train_recipe: $*"; }

# run_step NAME CMD...: runs CMD once. The stamp holds the command line: a finished step with the
# same command is skipped, one with another command stops the script (the sizes changed: use
# another --out). Wall, user and system seconds go to costs/NAME.time (one line per run).
run_step() {
  local name=$1; shift
  # The binary is not a setting: the stamp holds the arguments.
  local stamp="$out/stamps/$name.done" cmd="${*:2}"
  if [[ -f "$stamp" ]]; then
    if [[ "$(cat "$stamp")" == "$cmd" ]]; then log "$name: done, skipped"; return 0; fi
    echo "train_recipe.sh: step $name was done in $out with another command:" >&2
    echo "  was: $(cat "$stamp")" >&2
    echo "  now: $cmd" >&2
    echo "use another --out (or remove $stamp and what the step wrote)" >&2
    exit 1
  fi
  log "$name: $cmd"
  /usr/bin/time -f "%e %U %S" -a -o "$out/costs/$name.time" "$@" >>"$out/logs/$name.log" 2>&1 ||
    { echo "train_recipe.sh: step $name failed; see $out/logs/$name.log" >&2; tail -n 20 "$out/logs/$name.log" >&2; exit 1; }
  echo "$cmd" >"$stamp"
}

# 1. Apartments.
run_step scenes "$phyir" scenes generate --preset apartment --count "$count" --seed "$seed" --out "$out/scenes"

# The dataset seed: the first from --dataset-seed whose split (dataset/src/split.cpp: SHA-256 of
# "phyir-dataset split|<seed>|<scene>", its first 53 bits as a fraction) gives the apartments a
# val and a test scene and at least the train fraction's share less one to train on, so the
# recipe never trains without validation or evaluates nothing.
data_seed=$(python3 - "$count" "$dataset_seed" "$split" <<'EOF'
import hashlib, sys
count, first, fractions = int(sys.argv[1]), int(sys.argv[2]), [float(x) for x in sys.argv[3].split(",")]
def split(seed, scene):
    u = (int(hashlib.sha256(f"phyir-dataset split|{seed}|{scene}".encode()).hexdigest()[:16], 16) >> 11) * 2.0**-53
    return "train" if u < fractions[0] else "val" if u < fractions[0] + fractions[1] else "test"
for seed in range(first, first + 1000):
    s = [split(seed, f"apartment_{i}") for i in range(count)]
    if "val" in s and "test" in s and s.count("train") >= max(1, round(count * fractions[0]) - 1):
        print(seed); break
else:
    sys.exit(f"no dataset seed in [{first}, {first + 1000}) gives {count} apartments a val and a test scene")
EOF
)
log "dataset seed $data_seed"

# 2. The dataset (phyir dataset generate completes an unfinished folder itself).
run_step dataset "$phyir" dataset generate --scenes "$out/scenes" --out "$out/data" --preset cpu \
  --width "$width" --height "$height" --spp "$spp" --probe-grid "$probe_grid" --probe-res "$probe_res" \
  --probe-spp "$probe_spp" --probe-cache-spp "$probe_cache_spp" --probe-cache-cell "$probe_cache_cell" \
  --views-per-scene "$views" \
  --seed "$data_seed" --split "$split" --threads "$dataset_threads" --quiet

# 3. Training. train_stage ARM STAGE EPOCHS INIT ARGS...: a stage's run (run_step's stamp and
# costs); when an earlier run was interrupted, the same command with --resume instead of --init.
train_stage() {
  local arm=$1 stage=$2 ep=$3 init=$4; shift 4
  local dir="$out/runs/$arm/$stage" name="train_${arm}_${stage}"
  local cmd=("$phyir" train --data "$out/data" --out "$dir" --stage "$stage" --epochs "$ep" --threads "$threads"
             --val-views "$val_views" --lr-schedule "$lr_schedule" --quiet "$@")
  [[ -z "$init" ]] || cmd+=(--init "$init")
  if [[ ! -f "$out/stamps/$name.done" && -f "$dir/checkpoint.pt" ]]; then
    local resume=("$phyir" train --data "$out/data" --out "$dir" --stage "$stage" --epochs "$ep" --threads "$threads"
                  --val-views "$val_views" --lr-schedule "$lr_schedule" --quiet "$@" --resume)
    log "$name: resuming $dir/checkpoint.pt"
    /usr/bin/time -f "%e %U %S" -a -o "$out/costs/$name.time" "${resume[@]}" >>"$out/logs/$name.log" 2>&1 ||
      { echo "train_recipe.sh: $name failed; see $out/logs/$name.log" >&2; tail -n 20 "$out/logs/$name.log" >&2; exit 1; }
    echo "${cmd[*]:1}" >"$out/stamps/$name.done"
  fi
  run_step "$name" "${cmd[@]}"
  if [[ -f "$dir/loss_curve.png" ]]; then cp "$dir/loss_curve.png" "$out/curves/${arm}_${stage}.png"; fi
}

config=(--input-height 128 --input-width 256 --render-height 32 --render-width 64 --probe-height 8 --probe-width 16
        --width-divisor "$width_divisor" --lnet-head "$lnet_head")
train_stage shared gmnet "$ep_gm" "" "${config[@]}" --lr "$gmnet_lr" --w-normal "$gmnet_w_normal" --seed 1
for arm in $arms; do
  # input is the default unit (and the shared GMNet checkpoint's): only the absolute arm says it.
  units=()
  [[ $arm == input ]] || units=(--target-units "$arm")
  train_stage "$arm" lnet "$ep_l" "$out/runs/shared/gmnet/checkpoint.pt" "${units[@]}" --lr "$lnet_lr" \
    --best-metric probe_ssim --seed 2
  train_stage "$arm" joint "$ep_j" "$out/runs/$arm/lnet/checkpoint.pt" --lr "$joint_lr" --seed 3
  train_stage "$arm" gsnet "$ep_gs" "$out/runs/$arm/joint/checkpoint.pt" --lr "$gsnet_lr" --seed 4
done

# 4. Evaluation on the test split, the baselines included (identical in both arms).
relight_args=()
[[ $relight == 1 ]] || relight_args=(--no-relight)
# Radiance metrics in absolute units (eval/<arm>) and in each view's input units
# (eval/<arm>_input, the same predictions): absolute errors weigh the sunlit views most.
for arm in $arms; do
  run_step "eval_$arm" "$phyir" eval --gt "$out/data" --split test --model "$out/runs/$arm/gsnet/checkpoint.pt" \
    --out "$out/eval/$arm" --model-threads "$threads" --threads "$threads" --quiet "${relight_args[@]}"
  run_step "eval_${arm}_input" "$phyir" eval --gt "$out/data" --split test --pred "$out/eval/$arm/pred" \
    --radiance input --out "$out/eval/${arm}_input" --threads "$threads" --quiet "${relight_args[@]}"
done

# 5. Results, costs.
python3 - "$out" "$arms" <<'EOF'
import csv, json, math, os, sys
out, arms = sys.argv[1], sys.argv[2].split()
manifest = json.load(open(os.path.join(out, "data", "manifest.json")))
per_split = {}
for v in manifest["views"]:
    per_split[v["split"]] = per_split.get(v["split"], 0) + 1

# Costs: every step's wall and CPU seconds; per view for the dataset, per step for training
# (steps = rows of train_log.csv).
cost_rows = []
for name in sorted(os.listdir(os.path.join(out, "costs"))):
    if not name.endswith(".time"):
        continue
    step = name[:-5]
    wall = user = system = 0.0
    for line in open(os.path.join(out, "costs", name)):
        parts = line.split()
        if len(parts) == 3:
            try:
                w, u, s = map(float, parts)
            except ValueError:
                continue  # a "Command exited with non-zero status" line
            wall, user, system = wall + w, user + u, system + s
    units, unit = "", ""
    if step == "dataset":
        units, unit = len(manifest["views"]), "view"
    elif step.startswith("train_"):
        arm, stage = step[len("train_"):].rsplit("_", 1)
        logf = os.path.join(out, "runs", arm, stage, "train_log.csv")
        if os.path.exists(logf):
            units, unit = sum(1 for _ in open(logf)) - 1, "step"
    elif step.startswith("eval_"):
        units, unit = per_split.get("test", 0), "view"
    row = {"step": step, "wall_s": round(wall, 1), "cpu_s": round(user + system, 1), "units": units, "unit": unit,
           "wall_s_per_unit": round(wall / units, 2) if units else "", "cpu_s_per_unit": round((user + system) / units, 2) if units else ""}
    cost_rows.append(row)
with open(os.path.join(out, "costs.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(cost_rows[0].keys()))
    w.writeheader()
    w.writerows(cost_rows)

# Results: every metric of the prediction of each arm and of the two baselines, with the
# radiance metrics in absolute and in input units, over all test views and per lighting.
METRICS = [("basecolor_mse", False), ("normal_deg", False), ("roughness_mse", False), ("metalness_mse", False),
           ("depth_abs_rel", False), ("depth_rmse", False), ("depth_delta1", True), ("rerender_mse", False),
           ("probe_ssim", True), ("relight_diffuse_mae", False), ("relight_matte_silver_mae", False),
           ("relight_mirror_silver_mae", False)]
RADIANCE = {"rerender_mse", "probe_ssim", "relight_diffuse_mae", "relight_matte_silver_mae", "relight_mirror_silver_mae"}
rooms = json.load(open(os.path.join(out, "scenes", "rooms.json")))["rooms"]
lighting = {os.path.splitext(r["file"])[0]: r.get("lighting", "?") for r in rooms}
def load(arm, units):
    path = os.path.join(out, "eval", arm if units == "absolute" else f"{arm}_{units}", "metrics.json")
    return json.load(open(path))["methods"] if os.path.exists(path) else None
def mean_of(methods, method, key, light):
    try:
        m = methods[method]
    except (KeyError, TypeError):
        return None
    if light == "all":
        v = m["mean"].get(key)
        return None if v is None or (isinstance(v, float) and math.isnan(v)) else float(v)
    vals = [pv[key] for vid, pv in m["per_view"].items()
            if lighting.get(vid.split("/")[0]) == light and pv.get(key) is not None and not math.isnan(pv[key])]
    return sum(vals) / len(vals) if vals else None
test_lights = sorted({lighting.get(v["id"].split("/")[0], "?") for v in manifest["views"] if v["split"] == "test"})
rows = []
for units in ("absolute", "input"):
    results = {arm: load(arm, units) for arm in arms}
    ref = next((a for a in arms if results[a]), None)
    for light in ["all"] + test_lights:
        for key, higher in METRICS:
            if (units == "input" or light != "all") and key not in RADIANCE:
                continue  # the maps have no radiance unit and are reported once
            row = {"metric": key, "units": units if key in RADIANCE else "-", "lighting": light,
                   "better": "higher" if higher else "lower"}
            for arm in arms:
                row[f"phyir_{arm}"] = mean_of(results[arm], "prediction", key, light)
            row["constant_mean"] = mean_of(results[ref], "constant_mean", key, light) if ref else None
            row["image_as_basecolor"] = mean_of(results[ref], "input_as_basecolor", key, light) if ref else None
            baselines = [b for b in (row["constant_mean"], row["image_as_basecolor"]) if b is not None]
            best = (max if higher else min)(baselines) if baselines else None
            row["best_baseline"] = best
            for arm in arms:
                p = row[f"phyir_{arm}"]
                # Margin: how much better than the best baseline, relative to it (positive = better).
                if p is None or best is None or best == 0:
                    row[f"margin_{arm}"] = None
                else:
                    row[f"margin_{arm}"] = (p - best) / abs(best) if higher else (best - p) / abs(best)
            if all(row.get(f"phyir_{a}") is None for a in arms) and best is None:
                continue
            rows.append(row)
fields = list(rows[0].keys()) if rows else ["metric"]
with open(os.path.join(out, "results.csv"), "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=fields)
    w.writeheader()
    for r in rows:
        w.writerow({k: ("" if v is None else (f"{v:.6g}" if isinstance(v, float) else v)) for k, v in r.items()})

def fmt(v, pct=False):
    if v is None:
        return "-"
    return f"{100 * v:+.0f}%" if pct else f"{v:.4g}"
test_views = {l: sum(1 for v in manifest["views"] if v["split"] == "test" and lighting.get(v["id"].split("/")[0]) == l)
              for l in test_lights}
lines = [f"# Training recipe results ({out})", "",
         f"Views: {len(manifest['views'])} ({', '.join(f'{k} {v}' for k, v in sorted(per_split.items()))}); "
         f"scenes {manifest.get('counts', {}).get('scenes', '?')} apartments; test views by lighting: "
         + ", ".join(f"{l} {n}" for l, n in test_views.items()) + ". Test-split means of `phyir eval` "
         f"(toolkit depth protocol); radiance metrics in absolute units (`--radiance absolute`) and in each "
         f"view's input units (`--radiance input`); margin = improvement over the better baseline, relative to it.", "",
         "| metric | units | lighting | better | " + " | ".join(f"PhyIR, {a} arm" for a in arms)
         + " | constant mean | image as base colour | " + " | ".join(f"margin ({a})" for a in arms) + " |",
         "| --- | --- | --- | --- | " + " | ".join("---" for _ in arms) + " | --- | --- | "
         + " | ".join("---" for _ in arms) + " |"]
for r in rows:
    lines.append(f"| {r['metric']} | {r['units']} | {r['lighting']} | {r['better']} | "
                 + " | ".join(fmt(r[f'phyir_{a}']) for a in arms)
                 + f" | {fmt(r['constant_mean'])} | {fmt(r['image_as_basecolor'])} | "
                 + " | ".join(fmt(r[f'margin_{a}'], True) for a in arms) + " |")
lines += ["", "## Costs", "", "| step | wall s | CPU s | per | wall s each | CPU s each |", "| --- | --- | --- | --- | --- | --- |"]
for c in cost_rows:
    lines.append(f"| {c['step']} | {c['wall_s']} | {c['cpu_s']} | {c['units']} {c['unit']}s | {c['wall_s_per_unit']} | {c['cpu_s_per_unit']} |")
lines += ["", "Curves: " + ", ".join(f"[{n}](curves/{n})" for n in sorted(os.listdir(os.path.join(out, 'curves')))), ""]
open(os.path.join(out, "results.md"), "w").write("\n".join(lines))
print("\n".join(lines))
EOF
log "done: $out/results.md, results.csv, costs.csv, curves/"

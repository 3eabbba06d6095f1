#!/usr/bin/env bash
# Training throughput with one process and with N local ranks (docs/model-scale.md "Training on
# several processes"): views per second over the steps after the first (the first pays the
# start-up and the allocator's warm-up) and each process's peak RSS, from train_log.csv and
# /usr/bin/time -v (a launcher's figure is the largest of its ranks'). One process gets
# THREADS threads, each of the N ranks THREADS / N, at the same global batch.
#   scripts/bench_train_ranks.sh DATA OUT SIZES STAGE BATCH STEPS [N] [THREADS] [extra train flags...]
#   SIZES: default (the network's defaults) or paper (input 256x512, rendering 128x256, probes 16x32)
# Writes OUT/results.csv (one row per run) and prints it.
set -euo pipefail
data=$1 out=$2 sizes=$3 stage=$4 batch=$5 steps=$6
nproc=${7:-2} threads=${8:-$(nproc)}
shift $(($# < 8 ? $# : 8))
phyir=${PHYIR:-$(dirname "$0")/../build/cli/phyir}
case "$sizes" in
  default) size_flags=() ;;
  paper) size_flags=(--input-height 256 --input-width 512 --render-height 128 --render-width 256
                     --probe-height 16 --probe-width 32) ;;
  *) echo "SIZES must be default or paper" >&2; exit 1 ;;
esac
mkdir -p "$out"
csv=$out/results.csv
[ -f "$csv" ] || echo "sizes,stage,batch,processes,threads_each,steps,seconds_per_step,views_per_second,peak_rss_gb_per_process,load_before" > "$csv"
run() {  # $1 = processes
  local n=$1 each=$((threads / $1)) dir=$out/$sizes-$stage-b$batch-p$1
  shift
  [ "$each" -ge 1 ] || each=1
  rm -rf "$dir"
  local load; load=$(cut -d' ' -f1 /proc/loadavg)
  local ranks=(); [ "$n" -gt 1 ] && ranks=(--nproc "$n")
  /usr/bin/time -v -o "$dir.time" "$phyir" --log-level warn train --data "$data" --split '' --out "$dir" \
    --stage "$stage" --batch "$batch" --epochs 1000 --max-steps "$steps" --threads "$each" --quiet \
    --val-split '' --no-augment "${size_flags[@]}" "${ranks[@]}" "$@"
  /usr/bin/python3 - "$dir/train_log.csv" "$dir.time" "$sizes,$stage,$batch,$n,$each" "$load" >> "$csv" << 'PY'
import csv, re, sys
rows = list(csv.DictReader(open(sys.argv[1])))
t = [float(r["seconds"]) for r in rows]
per_step = (t[-1] - t[0]) / (len(t) - 1)
batch = int(sys.argv[3].split(",")[2])
rss = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", open(sys.argv[2]).read()).group(1)) / 1e6 * 1.024
print(f"{sys.argv[3]},{len(rows)},{per_step:.3f},{batch / per_step:.3f},{rss:.2f},{sys.argv[4]}")
PY
}
run 1 "$@"
run "$nproc" "$@"
cat "$csv"

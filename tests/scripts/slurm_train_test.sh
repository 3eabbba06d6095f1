#!/usr/bin/env bash
# `phyir train slurm` on a real single-node Slurm cluster on localhost (lib/local_slurm.sh:
# installs slurm-wlm and munge with apt-get if missing, as root; prints SKIPPED when that is
# impossible). The joint stage of a small network (GMNet with BatchNorm, LNet, the rendering
# layer) on a tiny generated dataset runs as one job of 2 tasks, one rank each, meeting at rank
# 0's TCP store, and is checked against the same training as one local process at the same
# global batch: both ranks joined, rank 0 wrote the checkpoint and logs, and every step's loss
# equals the local run's to 1e-5 relative (docs/model-scale.md "Training on several processes").
#   $1 = phyir binary, $2 = scratch folder (emptied).
set -euo pipefail
phyir=$1
work=$2
source "$(dirname "${BASH_SOURCE[0]}")/lib/local_slurm.sh"
enter_slurm_scratch
"$phyir" train --help | grep -q -- "--nproc" || skip "this phyir has no training (built with PHYIR_BUILD_MODEL=OFF)"
start_local_slurm

"$phyir" --log-level warn scenes generate --out rooms --count 2 --seed 2 --preset mini
"$phyir" --log-level warn dataset generate --scenes rooms --out data --preset tiny --views-per-scene 2 \
  --probe-grid 16x32 --probe-res 8x16 --threads 2 --quiet
flags=(--data data --split '' --stage joint --epochs 2 --batch 2 --seed 3 --lr 1e-4 --input-height 32
  --input-width 64 --render-height 16 --render-width 32 --probe-height 8 --probe-width 16 --width-divisor 4
  --threads 1 --quiet --val-split '')
"$phyir" train slurm --ntasks 2 --cpus-per-task 1 --time 00:10:00 --submit -- "${flags[@]}" --out cluster \
  > submit.log 2>&1 || die "submission failed: $(cat submit.log)"
cat submit.log
job=$(sed -n 's/^job=\([0-9]*\).*/\1/p' submit.log)
[ -n "$job" ] || die "no job id in the submission output"
grep -q -- 'srun --kill-on-bad-exit=1' cluster/slurm/train.sbatch || die "the script does not end the job when a rank fails"

# Meanwhile, the same training as one local process.
"$phyir" --log-level warn train "${flags[@]}" --out local

wait_for_jobs 300
echo "job done after $(($(date +%s) - start)) s"
log=cluster/slurm/logs/train-$job.log
[ -s "$log" ] || die "no job log ($log)"
for r in 0 1; do
  grep -q "rank $r of 2 joining at tcp:" "$log" || die "rank $r did not start: $(tail -20 "$log")"
done
[ -f cluster/checkpoint.pt ] || die "no checkpoint: $(tail -20 "$log")"
grep -q '"ranks": 2' cluster/train_log.json || die "train_log.json does not say 2 ranks"
[ ! -e cluster/rank-1.log ] || die "rank 1 wrote files"
/usr/bin/python3 - cluster/train_log.csv local/train_log.csv << 'PY' || die "the losses differ from the local run"
import csv, sys
a, b = ([float(r["loss"]) for r in csv.DictReader(open(p))] for p in sys.argv[1:])
print("cluster", a, "\nlocal  ", b)
assert len(a) == len(b) == 4, (len(a), len(b))
assert all(abs(x - y) <= 1e-5 * abs(y) for x, y in zip(a, b))
PY
echo "slurm_train_test: OK (2 ranks under Slurm train as 1 process, $(($(date +%s) - start)) s)"

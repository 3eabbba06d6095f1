#!/usr/bin/env bash
# `phyir dataset slurm` on a real single-node Slurm cluster on localhost: installs Debian's
# slurm-wlm and munge with apt-get if missing (as root; prints SKIPPED and exits 0 when that
# is impossible), starts munged, slurmctld and slurmd from a private config in the scratch
# folder (own munge socket and key, free ports, no systemd), submits the job array for a tiny
# dataset (tiny preset, 2 mini rooms x 2 views, 2 shards) with --submit, polls squeue until
# the array and the dependent merge + verify job are gone (accounting is off: no sacct), and
# checks: both tasks and the merge job wrote their logs, the merge job's verify said OK, our
# own verify passes, and the dataset equals a local unsharded run byte for byte. A trap
# cancels left-over jobs and stops the three daemons by their pid files (lib/local_slurm.sh).
#   $1 = phyir binary, $2 = scratch folder (emptied).
set -euo pipefail
phyir=$1
work=$2
source "$(dirname "${BASH_SOURCE[0]}")/lib/local_slurm.sh"
enter_slurm_scratch
start_local_slurm

# --- the dataset on the cluster -------------------------------------------------------------
"$phyir" --log-level warn scenes generate --out rooms --count 2 --seed 2 --preset mini
settings=(--preset tiny --views-per-scene 2)
"$phyir" dataset slurm --scenes rooms --out data "${settings[@]}" --shards 2 --cpus-per-task 1 \
  --time 00:10:00 --submit > submit.log 2>&1 || die "submission failed: $(cat submit.log)"
cat submit.log
array=$(sed -n 's/.*array_job=\([0-9]*\).*/\1/p' submit.log)
merge=$(sed -n 's/.*merge_job=\([0-9]*\).*/\1/p' submit.log)
[ -n "$array" ] && [ -n "$merge" ] || die "no job ids in the submission output"
grep -q -- "--dependency=afterok:\${array}" data/slurm/submit.sh || die "submit.sh lacks the afterok dependency"

# Meanwhile, the same dataset locally, unsharded, for the byte comparison.
"$phyir" --log-level warn dataset generate --scenes rooms --out local "${settings[@]}" --threads 1 --quiet

wait_for_jobs 150
echo "jobs done after $(($(date +%s) - start)) s"

for i in 0 1; do
  log=data/slurm/logs/generate-${array}_$i.log
  [ -s "$log" ] || die "no log for array task $i ($log)"
  grep -q "shard $i/2" "$log" || die "task $i log does not name its shard: $(cat "$log")"
  [ -f "data/shards/shard-$i-of-2/manifest.json" ] || die "shard $i did not finish: $(tail -5 "$log")"
done
mlog=data/slurm/logs/merge-$merge.log
[ -s "$mlog" ] || die "the merge job did not run (no $mlog); array logs: $(tail -3 data/slurm/logs/generate-*.log)"
grep -q "data: 4 views, .* checked: OK" "$mlog" || die "the merge job's verify did not pass: $(cat "$mlog")"
"$phyir" --log-level warn dataset verify data > verify.log || { cat verify.log; die "verify failed"; }
diff -r -x timing.json -x shards -x slurm local data > diff.log || { head -20 diff.log; die "the Slurm dataset differs from the local run"; }
echo "slurm_dataset_test: OK (2 array tasks + dependent merge/verify on a local Slurm, $(($(date +%s) - start)) s)"

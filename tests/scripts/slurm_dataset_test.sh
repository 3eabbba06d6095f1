#!/usr/bin/env bash
# `phyir dataset slurm` on a real single-node Slurm cluster on localhost: installs Debian's
# slurm-wlm and munge with apt-get if missing (as root; prints SKIPPED and exits 0 when that
# is impossible), starts munged, slurmctld and slurmd from a private config in the scratch
# folder (own munge socket and key, free ports, no systemd), submits the job array for a tiny
# dataset (tiny preset, 2 mini rooms x 2 views, 2 shards) with --submit, polls squeue until
# the array and the dependent merge + verify job are gone (accounting is off: no sacct), and
# checks: both tasks and the merge job wrote their logs, the merge job's verify said OK, our
# own verify passes, and the dataset equals a local unsharded run byte for byte. A trap
# cancels left-over jobs and stops the three daemons by their pid files.
#   $1 = phyir binary, $2 = scratch folder (emptied).
set -euo pipefail
phyir=$1
work=$2
# Daemons of an earlier run that was killed before its trap ran (e.g. a ctest timeout):
# stop them by their pid files before those files are deleted.
for f in "$work/slurm/slurmd.pid" "$work/slurm/slurmctld.pid" "$work/munge/munged.pid"; do
  [ -f "$f" ] || continue
  pid=$(cat "$f")
  case "$(cat "/proc/$pid/comm" 2> /dev/null)" in
    slurmd | slurmctld | munged) kill "$pid" 2> /dev/null; sleep 1 ;;
  esac
done
rm -rf "$work"
mkdir -p "$work"
cd "$work"
work=$(pwd)
die() { echo "FAIL: $*" >&2; exit 1; }
skip() { echo "SKIPPED: $*"; exit 0; }
start=$(date +%s)

# --- Slurm and munge from Debian -------------------------------------------------------
have_all() { command -v slurmctld && command -v slurmd && command -v sbatch && command -v squeue && command -v munged; } > /dev/null 2>&1
if ! have_all; then
  [ "$(id -u)" -eq 0 ] || skip "slurm-wlm/munge are not installed and installing them needs root"
  command -v apt-get > /dev/null || skip "slurm-wlm/munge are not installed and there is no apt-get"
  echo "installing slurm-wlm and munge with apt-get"
  export DEBIAN_FRONTEND=noninteractive
  # Package scripts must not start daemons on this machine (no systemd; we start our own).
  policy=/usr/sbin/policy-rc.d
  restore_policy=0
  if [ ! -e "$policy" ]; then printf '#!/bin/sh\nexit 101\n' > "$policy"; chmod +x "$policy"; restore_policy=1; fi
  ok=1
  apt-get install -y -qq --no-install-recommends slurm-wlm munge > apt.log 2>&1 ||
    { apt-get update -qq > /dev/null 2>&1 && apt-get install -y -qq --no-install-recommends slurm-wlm munge >> apt.log 2>&1; } || ok=0
  [ "$restore_policy" = 1 ] && rm -f "$policy"
  [ "$ok" = 1 ] || skip "apt-get could not install slurm-wlm and munge (see $work/apt.log)"
  have_all || skip "slurm-wlm installed but its daemons are not on PATH"
fi
[ "$(id -u)" -eq 0 ] || skip "the single-node cluster runs its daemons as root (SlurmUser=root); run as root"

# --- a private cluster ----------------------------------------------------------------------
mkdir -p munge slurm/state slurm/spool
chmod 700 munge
munge_pid=$work/munge/munged.pid
ctld_pid=$work/slurm/slurmctld.pid
slurmd_pid=$work/slurm/slurmd.pid
cleanup() {
  set +e
  if [ -n "${SLURM_CONF:-}" ] && [ -f "$ctld_pid" ]; then
    ids=$(squeue -h -o %A 2> /dev/null)
    [ -n "$ids" ] && scancel $ids 2> /dev/null && sleep 2
  fi
  for f in "$slurmd_pid" "$ctld_pid" "$munge_pid"; do
    [ -f "$f" ] || continue
    pid=$(cat "$f")
    kill "$pid" 2> /dev/null
    for _ in $(seq 1 50); do kill -0 "$pid" 2> /dev/null || break; sleep 0.1; done
    kill -0 "$pid" 2> /dev/null && kill -9 "$pid" 2> /dev/null
  done
}
trap cleanup EXIT

dd if=/dev/urandom of=munge/munge.key bs=1024 count=1 status=none
chmod 400 munge/munge.key
munged --force --key-file="$work/munge/munge.key" --socket="$work/munge/munge.socket" \
  --pid-file="$munge_pid" --log-file="$work/munge/munged.log" --seed-file="$work/munge/munged.seed" ||
  die "munged did not start: $(tail -5 munge/munged.log 2> /dev/null)"

read -r ctld_port slurmd_port < <(/usr/bin/python3 -c '
import socket
ports = []
socks = []
for _ in range(2):
    s = socket.socket(); s.bind(("127.0.0.1", 0)); socks.append(s); ports.append(s.getsockname()[1])
print(*ports)')
node=$(hostname -s)
cat > slurm/slurm.conf <<CONF
# Written by tests/scripts/slurm_dataset_test.sh: one node, root, no systemd, no accounting.
ClusterName=phyirtest
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$work/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$work/slurm/state
SlurmdSpoolDir=$work/slurm/spool
SlurmctldPidFile=$ctld_pid
SlurmdPidFile=$slurmd_pid
SlurmctldLogFile=$work/slurm/slurmctld.log
SlurmdLogFile=$work/slurm/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
SchedulerType=sched/builtin
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
MinJobAge=2
KillWait=5
InactiveLimit=0
NodeName=$node NodeAddr=127.0.0.1 CPUs=2 State=UNKNOWN
PartitionName=test Nodes=$node Default=YES MaxTime=INFINITE State=UP
CONF
export SLURM_CONF=$work/slurm/slurm.conf
slurmctld -f "$SLURM_CONF" || die "slurmctld did not start: $(tail -5 slurm/slurmctld.log)"
slurmd -f "$SLURM_CONF" -N "$node" || die "slurmd did not start: $(tail -5 slurm/slurmd.log)"
for _ in $(seq 1 100); do
  state=$(sinfo -h -n "$node" -o %t 2> /dev/null || true)
  [ "$state" = idle ] && break
  sleep 0.2
done
[ "$state" = idle ] || die "the node did not become idle (state '$state'): $(tail -5 slurm/slurmctld.log)"
echo "slurm up after $(($(date +%s) - start)) s: node $node idle, ports $ctld_port/$slurmd_port"

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

deadline=$(($(date +%s) + 150))
while :; do
  left=$(squeue -h -o '%A %T' 2> /dev/null) || die "squeue failed"
  [ -z "$left" ] && break
  [ "$(date +%s)" -lt "$deadline" ] || die "jobs still queued after 150 s: $left; $(tail -3 slurm/slurmctld.log)"
  sleep 1
done
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

# A private single-node Slurm cluster on localhost for the Slurm tests (sourced; $work is the
# test's scratch folder). Installs
# Debian's slurm-wlm and munge with apt-get if missing (as root; skip() when that is impossible),
# starts munged, slurmctld and slurmd from a private config in $work (own munge socket and key,
# free ports, no systemd, no accounting), exports SLURM_CONF, and traps EXIT to cancel left-over
# jobs and stop the three daemons by their pid files. wait_for_jobs SECONDS polls squeue until
# the queue is empty.

# The tests' start: stops an earlier run's daemons, empties $work and enters it, defines die()
# and skip(), and notes the start time.
enter_slurm_scratch() {
  stop_stale_slurm "$work"
  rm -rf "$work"
  mkdir -p "$work"
  cd "$work"
  work=$(pwd)
  start=$(date +%s)
}
die() { echo "FAIL: $*" >&2; exit 1; }
skip() { echo "SKIPPED: $*"; exit 0; }

# Daemons of an earlier run that was killed before its trap ran (e.g. a ctest timeout): stop
# them by their pid files before the scratch folder is emptied. Call before emptying $work.
stop_stale_slurm() {
  local f pid
  for f in "$1/slurm/slurmd.pid" "$1/slurm/slurmctld.pid" "$1/munge/munged.pid"; do
    [ -f "$f" ] || continue
    pid=$(cat "$f")
    case "$(cat "/proc/$pid/comm" 2> /dev/null)" in
      slurmd | slurmctld | munged) kill "$pid" 2> /dev/null; sleep 1 ;;
    esac
  done
}

# Starts the cluster (the daemons' files in $work/munge and $work/slurm); $work must be the
# current folder. Not indented: the body holds a here-document.
start_local_slurm() {
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

}

wait_for_jobs() {
  local deadline left
  deadline=$(($(date +%s) + $1))
  while :; do
    left=$(squeue -h -o '%A %T' 2> /dev/null) || die "squeue failed"
    [ -z "$left" ] && break
    [ "$(date +%s)" -lt "$deadline" ] || die "jobs still queued after $1 s: $left; $(tail -3 "$work/slurm/slurmctld.log")"
    sleep 1
  done
}

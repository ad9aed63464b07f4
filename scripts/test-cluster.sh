#!/usr/bin/env bash
# The cluster test: a real one-node Slurm on this machine runs a regime map
# as a job array of shards and a dependent merge job (examples/slurm/), and
# the merged map must be the unsharded run's output byte for byte.
#
#   scripts/test-cluster.sh            install Slurm if missing, run the test
#   scripts/test-cluster.sh --shards N split the map into N shards (default 4)
#   GS_MAP_ARGS="--omega-points 48 ..." scripts/test-cluster.sh   another map
#   KEEP=1 scripts/test-cluster.sh     keep the folder with the shards, logs
#
# Installs Debian's slurm-wlm and munge with apt-get when they are missing
# (idempotent: nothing is installed twice) and fails with the reason when it
# cannot (no apt-get, not root and no sudo, a daemon that does not start).
# Starts munged if no munge daemon answers, then a slurmctld and a slurmd
# of its own (ports 16817/16818, every state, spool, pid and log file in a
# temporary folder, no cgroups, no systemd), and stops what it started when
# it ends, by the daemons' pid files. Waits for events (the node idle, the
# merge job ended: sbatch --wait), never for a fixed time; a deadline only
# stops a hang. Prints each step's time.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
shards=4
case "${1:-}" in
  --shards)
    shards=${2:-}
    [[ "$shards" =~ ^[1-9][0-9]?$ ]] || { echo "test-cluster.sh: --shards $shards: allowed 1 ..= 99" >&2; exit 2; }
    ;;
  "") ;;
  *) echo "test-cluster.sh: unknown option '$1' (allowed: --shards N)" >&2; exit 2 ;;
esac

say() { printf '[cluster] %s\n' "$*"; }
fail() { printf '[cluster] FAILED: %s\n' "$*" >&2; exit 1; }
t0=$SECONDS
lap=$SECONDS
took() { say "$1 ($((SECONDS - lap)) s)"; lap=$SECONDS; }

SUDO=""
if (( EUID != 0 )); then
  command -v sudo >/dev/null || fail "not root and no sudo: cannot install or start Slurm and munge"
  SUDO=sudo
fi

# 1. Slurm and munge, installed once.
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null \
  || ! command -v sbatch >/dev/null || ! command -v munged >/dev/null; then
  command -v apt-get >/dev/null || fail "Slurm is not installed and there is no apt-get to install Debian's slurm-wlm and munge"
  say "installing Debian's slurm-wlm and munge (apt-get; about a minute, once)"
  $SUDO apt-get update -qq || fail "apt-get update failed"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq slurm-wlm munge >/dev/null \
    || fail "apt-get install slurm-wlm munge failed"
  took "installed $(slurmctld -V)"
else
  say "present: $(slurmctld -V), munge"
fi

# 2. munge: the key, its run folder, the daemon (left running if it was).
if ! munge -n 2>/dev/null | unmunge >/dev/null 2>&1; then
  if [[ ! -s /etc/munge/munge.key ]]; then
    $SUDO mkdir -p /etc/munge
    $SUDO dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
  fi
  $SUDO chown munge:munge /etc/munge/munge.key
  $SUDO chmod 400 /etc/munge/munge.key
  $SUDO mkdir -p /run/munge
  $SUDO chown munge:munge /run/munge
  $SUDO runuser -u munge -- munged || fail "munged did not start (see /var/log/munge/munged.log)"
  munge -n | unmunge >/dev/null || fail "munge -n | unmunge does not say Success"
  # Ours to stop at the end.
  started_munged=$(cat /run/munge/munged.pid)
  took "munged started"
fi

# 3. The one-node cluster, in a folder of its own.
work=$(mktemp -d /tmp/gearshock-cluster.XXXXXX)
host=$(hostname -s)
cpus=$(nproc)
conf=$work/slurm.conf
export SLURM_CONF=$conf
stop() {
  for d in slurmd slurmctld; do
    if [[ -s "$work/$d.pid" ]]; then
      pid=$(cat "$work/$d.pid")
      $SUDO kill "$pid" 2>/dev/null || true
      # Until it has gone (its pid file names it): at most 10 s.
      for _ in $(seq 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    fi
  done
  if [[ -n "${started_munged:-}" ]]; then $SUDO kill "$started_munged" 2>/dev/null || true; fi
  if [[ -n "${KEEP:-}" ]]; then say "kept $work"; else $SUDO rm -rf "$work"; fi
}
trap stop EXIT
mkdir -p "$work/state" "$work/spool" "$work/log" "$work/out"
cat > "$conf" <<CONF
ClusterName=gearshock
SlurmctldHost=$host
SlurmctldPort=16817
SlurmdPort=16818
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
MpiDefault=none
StateSaveLocation=$work/state
SlurmdSpoolDir=$work/spool
SlurmctldPidFile=$work/slurmctld.pid
SlurmdPidFile=$work/slurmd.pid
SlurmctldLogFile=$work/log/slurmctld.log
SlurmdLogFile=$work/log/slurmd.log
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=gearshock Nodes=$host Default=YES MaxTime=INFINITE State=UP
CONF
$SUDO env SLURM_CONF="$conf" slurmctld -f "$conf" \
  || fail "slurmctld did not start: $(tail -n 3 "$work/log/slurmctld.log" 2>/dev/null)"
$SUDO env SLURM_CONF="$conf" slurmd -f "$conf" \
  || fail "slurmd did not start: $(tail -n 3 "$work/log/slurmd.log" 2>/dev/null)"
# The node's state is the event: idle once slurmd has registered.
deadline=$((SECONDS + 60))
until [[ "$(sinfo -h -n "$host" -o %t 2>/dev/null)" == idle ]]; do
  (( SECONDS < deadline )) || fail "the node is not idle after 60 s: sinfo says '$(sinfo -h -o %t 2>&1)'; $(tail -n 3 "$work/log/slurmd.log" 2>/dev/null)"
  sleep 0.2
done
took "slurmctld and slurmd up, node $host idle ($cpus CPUs)"

# 4. The binary, the map, the jobs.
cargo build --release -q -p cli
gearshock=$root/target/release/gearshock
took "gearshock built (release)"
map=(--model gear-pair --omega-from 0.3 --omega-to 1.8 --omega-points 24
  --key te_um --value-from 0 --value-to 60 --value-points 8
  --transient-periods 150 --record-periods 40)
# GS_MAP_ARGS replaces the map (e.g. a larger one, to time the cluster).
if [[ -n "${GS_MAP_ARGS:-}" ]]; then read -r -a map <<< "$GS_MAP_ARGS"; fi
t_jobs=$SECONDS
GEARSHOCK=$gearshock timeout 900 examples/slurm/submit.sh --wait "$shards" "$work/out" "${map[@]}" \
  || fail "the jobs did not end well; $(tail -n 5 "$work"/out/slurm-*.out 2>/dev/null)"
took "array of $shards shards and the merge job done: $((SECONDS - t_jobs)) s from submission"
[[ -s "$work/out/map.json" ]] || fail "no merged map at $work/out/map.json"

# 5. A failing shard fails the run: the merge is cancelled (its dependency
# can no longer be met), submit.sh --wait says so, and no map is written.
bad=(--model gear-pair --omega-from 0.3 --omega-to 1.8 --omega-points 1
  --key te_um --value-from 0 --value-to 60 --value-points 2)
if GEARSHOCK=$gearshock timeout 300 examples/slurm/submit.sh --wait 2 "$work/bad" "${bad[@]}" \
  > "$work/bad.log" 2>&1; then
  fail "a run whose shards fail (--omega-points 1) was reported as done: $(cat "$work/bad.log")"
fi
[[ ! -e "$work/bad/map.json" ]] || fail "a failed run left a map: $work/bad/map.json"
grep -q "omega-points" "$work"/bad/slurm-*_0.out \
  || fail "the failed shard's output does not name the bad flag: $(cat "$work"/bad/slurm-*_0.out)"
took "a failing shard: the merge job cancelled, no map written, the shard's output names --omega-points"

# 6. The merged map is the unsharded run, byte for byte.
"$gearshock" map "${map[@]}" > "$work/whole.json"
took "unsharded run on one core"
if ! cmp "$work/whole.json" "$work/out/map.json"; then
  fail "the merged map differs from the unsharded run (diff $work/whole.json $work/out/map.json; KEEP=1 keeps them)"
fi
say "merged map of $shards shards = the unsharded run, byte for byte ($(wc -c < "$work/whole.json") bytes)"
say "passed in $((SECONDS - t0)) s"

#!/usr/bin/env bash
# Submits a regime map to Slurm as a job array of N shards and a merge job
# that runs when all of them have succeeded:
#
#   examples/slurm/submit.sh [--wait] N OUT [gearshock map arguments...]
#
# e.g. a research-size map, 400 x 200 cells at 3 000 recorded periods, in
# 100 shards of 2 rows each:
#
#   examples/slurm/submit.sh 100 /scratch/map --model gear-pair \
#     --omega-from 0.2 --omega-to 2 --omega-points 400 --key te_um \
#     --value-from 0 --value-to 100 --value-points 200 \
#     --transient-periods 1000 --record-periods 3000
#
# Prints the array's and the merge's job ids. OUT/map.json appears when the
# merge is done; OUT/slurm-*.out hold each task's messages. With --wait it
# returns when the merge job has ended, with its exit code (sbatch --wait);
# the merge is cancelled if a shard fails (--kill-on-invalid-dep), so a
# failed array ends the wait too. GEARSHOCK names the binary (default: the
# one on PATH); extra sbatch options go in SBATCH_OPTIONS (e.g. a
# partition or --time), shared by both jobs.
set -euo pipefail
wait=()
if [[ "${1:-}" == --wait ]]; then wait=(--wait); shift; fi
if (( $# < 2 )) || ! [[ "$1" =~ ^[1-9][0-9]*$ ]]; then
  echo "usage: $0 [--wait] N OUT [gearshock map arguments...] (N: the number of shards, 1 or more)" >&2
  exit 2
fi
n=$1 out=$2; shift 2
here=$(cd "$(dirname "$0")" && pwd)
gearshock=${GEARSHOCK:-$(command -v gearshock || true)}
if [[ ! -x "$gearshock" ]]; then
  echo "$0: no gearshock binary: set GEARSHOCK or put gearshock on PATH (cargo build --release -p cli)" >&2
  exit 2
fi
mkdir -p "$out"
out=$(cd "$out" && pwd)
export GEARSHOCK=$gearshock GS_SHARDS=$n GS_OUT=$out
# shellcheck disable=SC2086 # SBATCH_OPTIONS is a list of options
array=$(sbatch --parsable ${SBATCH_OPTIONS:-} --array="0-$((n - 1))" \
  --output="$out/slurm-%A_%a.out" --export=ALL "$here/shard.sbatch" "$@")
array=${array%%;*}
echo "array job $array: $n shards"
rc=0
# shellcheck disable=SC2086
merge=$(sbatch --parsable ${SBATCH_OPTIONS:-} "${wait[@]}" --dependency="afterok:$array" \
  --kill-on-invalid-dep=yes --output="$out/slurm-%j.out" --export=ALL "$here/merge.sbatch") || rc=$?
merge=${merge%%;*}
echo "merge job $merge: $out/map.json"
if (( ${#wait[@]} )); then
  # sbatch --wait returns 0 for a job cancelled before it ran (its
  # dependency failed): the job's own record says how it ended.
  state=$(scontrol show job -o "$merge" 2>/dev/null | grep -o 'JobState=[A-Z_]*' || true)
  if [[ "$state" != JobState=COMPLETED ]]; then
    echo "$0: the merge job did not complete (${state:-no job record}; exit code $rc): a shard failed? see $out/slurm-*.out" >&2
    (( rc != 0 )) || rc=1
  fi
elif (( rc != 0 )); then
  echo "$0: sbatch failed with exit code $rc" >&2
fi
exit "$rc"

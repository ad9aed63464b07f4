#!/bin/bash
# Runs a fixed set of 102 gearshock invocations (every subcommand's help,
# json, csv and jsonl outputs, shards and merges, figure shards merged into
# files, --progress lines and refusals) and stores stdout, stderr, exit code
# and the files written in OUTDIR. Two builds give the same outputs when
# `diff -r OUT1 OUT2` is empty: the check of a refactoring that must change
# nothing. Both binaries must have the same
# file name (clap prints it in the usage lines).
#
# usage: scripts/cli-outputs.sh path/to/gearshock OUTDIR
if [ $# -ne 2 ] || [ ! -x "$1" ] || [ -e "$2" -a ! -d "$2/work" ]; then
  echo "usage: $0 path/to/gearshock OUTDIR (a new folder, or one this script made)" >&2; exit 2
fi
BIN=$(realpath "$1"); OUT=$(realpath -m "$2")
rm -rf "$OUT"; mkdir -p "$OUT/work"; cd "$OUT/work" || exit 2
echo '{"model":"gear-pair","backlash_um":50}' > gp.json
echo '[1,2]' > notobj.json
n=0
run() { n=$((n+1)); local id=$(printf %03d $n); echo "$*" > "../$id.cmd"
  "$BIN" "$@" > "../$id.out" 2> "../$id.err"; echo $? > "../$id.rc"; }
B="--omega-from 0.4 --omega-to 0.6 --points 5 --transient-periods 20 --record-periods 4"
M="--omega-from 0.4 --omega-to 0.6 --omega-points 3 --value-from 40 --value-to 80 --value-points 2 --transient-periods 20 --record-periods 4"
L="--omega-from 0.4 --omega-to 0.6 --points 3 --transient-periods 20 --periods 10"
F="--omega-from 0.3 --omega-to 0.8 --points 20 --harmonics 3"
S="--omega 0.5 --transient-periods 20 --record-periods 5"
run --help; run --version; run nosuch
for c in params keys modes simulate bifurcation frf map lyapunov instability merge presets figure bench; do run $c --help; done
run params; run params --format csv; run params --format jsonl; run params --model gear-pair
run params --set backlash_um=50 --set te_um=10; run params --params gp.json; run params --params notobj.json
run params --params missing.json; run params --set model=gear-pair --model ravigneaux; run params --set nokey=1
run params --set backlash_um=-5; run params --set backlash
run keys; run keys --markdown
run modes; run modes --format csv; run modes --format jsonl; run modes --model gear-pair
run simulate $S; run simulate $S --format csv; run simulate $S --format jsonl; run simulate $S --mesh s2b1
run simulate $S --mesh nope; run simulate $S --max-order -1; run simulate --omega 50; run simulate $S --model gear-pair --mesh pg
run bifurcation $B; run bifurcation $B --format csv; run bifurcation $B --format jsonl; run bifurcation $B --direction both
run bifurcation $B --mesh all; run bifurcation $B --chains 2; run bifurcation $B --direction sideways
run bifurcation $B --shard 1/3 --chains 2; run bifurcation $B --shard 5/3; run bifurcation $B --progress
run bifurcation --omega-from 0.4 --omega-to 0.6 --points 100000 --transient-periods 3000
run bifurcation --omega-from 0.4 --omega-to 0.6 --points 5000 --record-periods 1000 --transient-periods 1
for i in 0 1 2; do run bifurcation $B --shard $i/3; cp ../$(printf %03d $n).out bs$i.json; done
run merge bs0.json bs1.json bs2.json; run merge bs0.json bs1.json; run merge; run merge notobj.json; run merge bs0.json --out d
run frf $F; run frf $F --format csv; run frf $F --format jsonl; run frf $F --direction down --mesh all
run frf --omega-from 0.3 --omega-to 0.8 --points 20 --harmonics 1 --method describing-function
run frf $F --method nope; run frf $F --direction sideways; run frf --omega-from 0.3 --omega-to 0.8 --points 100000 --harmonics 40
run frf $F --progress; run frf $F --no-stability --method aft --grid 64
run map $M; run map $M --format csv; run map $M --format jsonl; run map $M --mesh s1a1 --key te_um
run map $M --key nokey; run map $M --progress
for i in 0 1; do run map $M --shard $i/2; cp ../$(printf %03d $n).out ms$i.json; done
run merge ms0.json ms1.json
run lyapunov $L; run lyapunov $L --format csv; run lyapunov $L --format jsonl; run lyapunov $L --progress
run lyapunov --omega-from 0.6 --omega-to 0.4; run lyapunov --omega-from 0.4 --omega-to 0.6 --points 1
run instability --omega-from 0.3 --omega-to 1.5 --points 20; run instability --omega-from 0.3 --omega-to 1.5 --points 20 --format csv
run instability --omega-from 0.3 --omega-to 1.5 --points 20 --format jsonl; run instability --omega-from 0.3 --omega-to 1.5 --points 1
run presets
run figure nope; run figure fig5; run figure fig5 --points 1 --out x
run figure fig5 --shard 0/3 --transient-periods 5 --record-periods 3; cp ../$(printf %03d $n).out f0.json
run figure fig5 --shard 1/3 --transient-periods 5 --record-periods 3; cp ../$(printf %03d $n).out f1.json
run figure fig5 --shard 2/3 --transient-periods 5 --record-periods 3; cp ../$(printf %03d $n).out f2.json
run merge f0.json f1.json f2.json --out figdir; run merge f0.json f1.json --out figdir2
run figure fig5 --transient-periods 5 --record-periods 3 --out figdir3
run bench --repeats 0
echo "$n invocations"

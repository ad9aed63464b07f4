#!/usr/bin/env bash
# gearshock's harmonic balance beside pyHarm's (the Python package
# pyharm-os), run here on the same sweep: `gearshock frf --omega-from 0.1
# --omega-to 0.5 --harmonics 7 --mesh s2b1` on the default compound set.
# Installs pyHarm into target/peer/venv if it is not there at the pinned
# version, builds the release binary, writes the harmonic-balance problem
# (gearshock bench --hbm-problem) and runs scripts/peer/pyharm_frf.py, which
# prints one JSON line per run (the CPU times, gearshock at its defaults
# and with the branch alone, --no-stability, as pyHarm computes no
# stability; both ratios; the branches' distance) and the medians. Usage:
# scripts/bench-pyharm.sh [RUNS] [more options of pyharm_frf.py, e.g.
# --nti 256 or --gearshock-args="--points 50"]
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-3}
shift || true
PYHARM_VERSION=1.2.2
venv=target/peer/venv
if ! "$venv/bin/python" -c "import importlib.metadata as m, sys; sys.exit(m.version('pyharm-os') != '$PYHARM_VERSION')" 2>/dev/null; then
  echo "installing pyharm-os $PYHARM_VERSION into $venv" >&2
  python3 -m venv "$venv"
  "$venv/bin/pip" install --quiet "pyharm-os==$PYHARM_VERSION"
fi
source scripts/env.sh
cargo build --release --quiet -p cli
bin=target/release/gearshock
mkdir -p target/peer
"$bin" bench --hbm-problem > target/peer/problem.json
# One thread each: gearshock is single-threaded, and so is pyHarm with
# single-threaded BLAS.
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 MKL_NUM_THREADS=1 NUMBA_NUM_THREADS=1
# From target/peer: pyHarm writes its own settings (.pyHarm/) where it runs.
root=$PWD
cd target/peer
exec "$root/$venv/bin/python" "$root/scripts/peer/pyharm_frf.py" --problem problem.json \
  --gearshock-bin "$root/$bin" --runs "$runs" "$@"

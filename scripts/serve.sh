#!/usr/bin/env bash
# Command 1: installs what is missing, builds the explorer page in release
# mode (offline: no tool downloads) and serves dist/ on 127.0.0.1:$PORT
# (default 8080), printing the URL and how long the start took.
set -euo pipefail
cd "$(dirname "$0")/.."
t0=$SECONDS
scripts/setup.sh
source scripts/env.sh
cargo fetch --quiet
if [[ -f dist/index.html ]]; then
  echo "[serve] building the page (only what changed since the last build; seconds)"
else
  echo "[serve] building the page for the first time: the solver and the page compiled to WebAssembly, twice (the page and its worker), then shrunk by wasm-opt (about 2 min on 2 cores)"
fi
trunk build --release --offline
echo "[serve] ready $((SECONDS - t0)) s after the start"
exec node scripts/static-server.mjs dist "${PORT:-8080}"

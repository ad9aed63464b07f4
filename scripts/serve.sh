#!/usr/bin/env bash
# Command 1: installs what is missing, builds the explorer page in release
# mode (offline: no tool downloads) and serves dist/ on 127.0.0.1:$PORT
# (default 8080), printing the URL.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
source scripts/env.sh
cargo fetch
trunk build --release --offline
exec node scripts/static-server.mjs dist "${PORT:-8080}"

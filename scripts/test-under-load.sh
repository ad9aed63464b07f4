#!/usr/bin/env bash
# The browser suite under load (issue 15, item 8): builds the release page
# once, starts two busy-loop processes that keep both cores of a two-core
# machine busy, then runs the whole browser suite three times in a row,
# stopping at the first failure. Prints pass or fail per run; the busy
# loops are killed on exit however the script ends.
#   scripts/test-under-load.sh [RUNS]   (RUNS defaults to 3)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh
runs="${1:-3}"

trunk build --release --offline

busy=()
cleanup() {
  for pid in "${busy[@]}"; do
    kill "$pid" 2>/dev/null || true
  done
}
trap cleanup EXIT
trap 'exit 130' INT TERM
for _ in 1 2; do
  node -e 'for (;;) {}' &
  busy+=("$!")
done
printf 'busy loops running: %s\n' "${busy[*]}"

for run in $(seq 1 "$runs"); do
  t0=$SECONDS
  if node --test --test-concurrency=1 tests/browser/; then
    printf '\n== run %d of %d under load: pass (%d s)\n' "$run" "$runs" "$((SECONDS - t0))"
  else
    printf '\n== run %d of %d under load: FAIL (%d s)\n' "$run" "$runs" "$((SECONDS - t0))"
    exit 1
  fi
done
printf '\n== all %d runs passed under load\n' "$runs"

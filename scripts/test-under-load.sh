#!/usr/bin/env bash
# The browser suite under load: builds the release page
# once, starts two busy loops (`yes > /dev/null`) that keep both cores of a
# two-core machine busy and a second headless chromium that loads the page
# again and again beside the suite (tests/browser/beside.mjs), then runs the
# whole browser suite three times in a row, stopping at the first failure.
# Prints pass or fail and the time per run; the load is stopped on exit
# however the script ends.
#   scripts/test-under-load.sh [RUNS]   (RUNS defaults to 3)
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh
runs="${1:-3}"

if [ "${SKIP_BUILD:-}" != 1 ]; then
  trunk build --release --offline
fi

busy=()
cleanup() {
  for pid in "${busy[@]}"; do
    kill "$pid" 2>/dev/null || true
  done
}
trap cleanup EXIT
trap 'exit 130' INT TERM
for _ in 1 2; do
  yes > /dev/null &
  busy+=("$!")
done
node tests/browser/beside.mjs > /tmp/gearshock-beside.log 2>&1 &
busy+=("$!")
printf 'busy loops and a second browser running: %s\n' "${busy[*]}"

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

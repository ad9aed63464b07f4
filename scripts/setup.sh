#!/usr/bin/env bash
# Installs what the browser build and tests need, skipping every tool that is
# already present at the right version (TOOLCHAIN.md): the wasm32 target,
# Trunk 0.21.14, wasm-bindgen-cli 0.2.130, the npm tools (wasm-opt from
# binaryen 132, playwright-core) and Debian's chromium. Safe to run again:
# a second run takes seconds. It exports nothing itself; callers put
# node_modules/.bin on PATH (scripts/env.sh).
#
#   scripts/setup.sh            install what is missing
#   scripts/setup.sh --dry-run  list what would be installed, install nothing
#
# The cold path is built for speed of building: the two tools are compiled
# with a release profile made for building fast (no LTO, 16 codegen units,
# opt-level 1, no debug info) instead of Trunk's own fat-LTO, one-codegen-unit
# profile, which is the slowest possible build of a dev server whose speed
# does not matter here. Trunk is built without its default features: they
# add a TLS stack (rustls, ring) for `trunk serve --tls` and a crates.io
# update check, neither used here (the page is served by
# scripts/static-server.mjs and every build is offline); 16 crates fewer.
# Trunk is compiled at opt-level 0: half the CPU time of opt-level 1 (354
# against 656 s), and a page build with it takes the same time (its work is
# wasm-bindgen's and wasm-opt's, separate programs); wasm-bindgen-cli keeps
# opt-level 1, since it rewrites the page's WebAssembly itself.
# Both tools compile side by side, each in its own
# target folder, while Debian's chromium, the npm tools and the project's
# crates download. Their compiler output goes to target/setup/*.log; the
# screen gets one line per step and a line a minute while a tool compiles.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh

TRUNK_VERSION=0.21.14
WASM_BINDGEN_VERSION=0.2.130
DRY_RUN=0
case "${1:-}" in
  --dry-run) DRY_RUN=1 ;;
  "") ;;
  *) echo "setup.sh: unknown option '$1' (allowed: --dry-run)" >&2; exit 2 ;;
esac

say() { printf '[setup] %s\n' "$*"; }
t_start=$SECONDS
LOGS=target/setup
mkdir -p "$LOGS"

# What is missing, decided once before anything starts.
need_target=0; need_trunk=0; need_bindgen=0; need_npm=0; need_chromium=0
rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown || need_target=1
trunk --version 2>/dev/null | grep -q "trunk ${TRUNK_VERSION}\$" || need_trunk=1
wasm-bindgen --version 2>/dev/null | grep -q "wasm-bindgen ${WASM_BINDGEN_VERSION}\$" || need_bindgen=1
stamp=node_modules/.package-lock.json
if ! [[ -f "$stamp" && ! package-lock.json -nt "$stamp" \
  && -x node_modules/.bin/wasm-opt && -d node_modules/playwright-core && -d node_modules/axe-core ]]; then
  need_npm=1
fi
[[ -x /usr/bin/chromium && -x /usr/bin/chromedriver ]] || need_chromium=1

if (( need_target )); then say "to install: the wasm32-unknown-unknown target (rustup; the page's compile target; about 20 s)"; else say "present: the wasm32-unknown-unknown target"; fi
if (( need_trunk )); then say "to install: trunk ${TRUNK_VERSION} from crates.io: the build tool that bundles the page (about 6 min on 2 cores, once)"; else say "present: trunk ${TRUNK_VERSION}"; fi
if (( need_bindgen )); then say "to install: wasm-bindgen-cli ${WASM_BINDGEN_VERSION} from crates.io: writes the JavaScript glue for the page's WebAssembly (about 6 min on 2 cores, once; side by side with trunk)"; else say "present: wasm-bindgen-cli ${WASM_BINDGEN_VERSION}"; fi
if (( need_npm )); then say "to install: npm ci: binaryen's wasm-opt 132 (shrinks the page's WebAssembly) and playwright-core (drives chromium in the browser tests; about 10 s)"; else say "present: node_modules (wasm-opt 132, playwright-core)"; fi
if (( need_chromium )); then say "to install: Debian's chromium and chromium-driver (apt-get): the headless browser of the browser tests (about 1 min)"; else say "present: chromium and chromium-driver"; fi
if (( DRY_RUN )); then
  say "dry run: nothing installed"
  exit 0
fi

if (( need_target )); then
  say "adding the wasm32-unknown-unknown target"
  rustup target add wasm32-unknown-unknown
fi

# Build profile for the two tools only (environment of those installs).
fast_install() {
  CARGO_PROFILE_RELEASE_LTO=false \
  CARGO_PROFILE_RELEASE_CODEGEN_UNITS=16 \
  CARGO_PROFILE_RELEASE_OPT_LEVEL="${TOOL_OPT_LEVEL:-1}" \
  CARGO_PROFILE_RELEASE_DEBUG=0 \
  CARGO_PROFILE_RELEASE_INCREMENTAL=false \
  CARGO_TERM_PROGRESS_WHEN=never \
  cargo install "$@"
}

pids=(); names=(); logs=()
start_bg() { # name log command...
  local name=$1 log=$2; shift 2
  "$@" >"$log" 2>&1 &
  pids+=($!); names+=("$name"); logs+=("$log")
}

if (( need_trunk )); then
  say "compiling trunk ${TRUNK_VERSION} (log: $LOGS/trunk.log)"
  start_bg "trunk ${TRUNK_VERSION}" "$LOGS/trunk.log" \
    env TOOL_OPT_LEVEL=0 CARGO_TARGET_DIR="$PWD/$LOGS/trunk-build" bash -c "$(declare -f fast_install); fast_install trunk --version ${TRUNK_VERSION} --locked --no-default-features"
fi
if (( need_bindgen )); then
  # Without --locked: its lock file names a crate version the registry lacks.
  say "compiling wasm-bindgen-cli ${WASM_BINDGEN_VERSION} (log: $LOGS/wasm-bindgen.log)"
  start_bg "wasm-bindgen-cli ${WASM_BINDGEN_VERSION}" "$LOGS/wasm-bindgen.log" \
    env CARGO_TARGET_DIR="$PWD/$LOGS/bindgen-build" bash -c "$(declare -f fast_install); fast_install wasm-bindgen-cli --version ${WASM_BINDGEN_VERSION}"
fi
if (( need_npm )); then
  say "npm ci (log: $LOGS/npm.log)"
  start_bg "npm ci" "$LOGS/npm.log" npm ci --no-audit --no-fund
fi
if (( need_chromium )); then
  SUDO=""
  if [[ "$(id -u)" != 0 ]]; then SUDO=sudo; fi
  say "installing Debian's chromium and chromium-driver (log: $LOGS/apt.log)"
  start_bg "chromium" "$LOGS/apt.log" bash -c "$SUDO apt-get update && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends chromium chromium-driver"
fi
if (( ${#pids[@]} > 0 )); then
  # The project's own crates download meanwhile, so the first build starts
  # at once (cargo fetch is quick when they are already there).
  start_bg "the project's crates (cargo fetch)" "$LOGS/fetch.log" cargo fetch
fi

# Wait for every background step, a line a minute while any runs; report
# each as it ends, and fail with its log's tail if it failed.
failed=0
declare -A done_at=()
last_tick=$SECONDS
while :; do
  running=0
  for i in "${!pids[@]}"; do
    [[ -n "${done_at[$i]:-}" ]] && continue
    if kill -0 "${pids[$i]}" 2>/dev/null; then
      running=1
    else
      rc=0; wait "${pids[$i]}" || rc=$?
      done_at[$i]=$SECONDS
      if (( rc == 0 )); then
        say "done: ${names[$i]} ($(( SECONDS - t_start )) s since the start)"
      else
        say "FAILED: ${names[$i]} (exit $rc); the end of ${logs[$i]}:"
        tail -n 20 "${logs[$i]}" >&2
        failed=1
      fi
    fi
  done
  (( running )) || break
  if (( SECONDS - last_tick >= 60 )); then
    last_tick=$SECONDS
    busy=()
    for i in "${!pids[@]}"; do [[ -z "${done_at[$i]:-}" ]] && busy+=("${names[$i]}"); done
    say "still working ($(( (SECONDS - t_start) / 60 )) min so far): ${busy[*]}"
  fi
  sleep 2
done
(( failed == 0 )) || exit 1

if ! wasm-opt --version 2>/dev/null | grep -q "version_132"; then
  echo "[setup] wasm-opt on PATH is not binaryen 132: $(command -v wasm-opt || echo none)" >&2
  exit 1
fi
# The tools' build folders are not needed once they are installed.
rm -rf "$LOGS/trunk-build" "$LOGS/bindgen-build"
say "ready in $(( SECONDS - t_start )) s"

#!/usr/bin/env bash
# Installs what the browser build and tests need, skipping every tool that is
# already present at the right version (TOOLCHAIN.md): the wasm32 target,
# Trunk 0.21.14, wasm-bindgen-cli 0.2.130, the npm tools (wasm-opt from
# binaryen 132, playwright-core) and Debian's chromium. Safe to run again:
# a second run takes seconds. Source it or run it; it exports nothing itself,
# callers put node_modules/.bin on PATH (scripts/env.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/env.sh

TRUNK_VERSION=0.21.14
WASM_BINDGEN_VERSION=0.2.130

say() { printf '[setup] %s\n' "$*"; }

if rustup target list --installed 2>/dev/null | grep -qx wasm32-unknown-unknown; then
  say "wasm32-unknown-unknown target: present"
else
  say "adding the wasm32-unknown-unknown target"
  rustup target add wasm32-unknown-unknown
fi

if trunk --version 2>/dev/null | grep -q "trunk ${TRUNK_VERSION}\$"; then
  say "trunk ${TRUNK_VERSION}: present"
else
  say "installing trunk ${TRUNK_VERSION} (about 10 minutes on 2 cores)"
  cargo install trunk --version "${TRUNK_VERSION}" --locked
fi

if wasm-bindgen --version 2>/dev/null | grep -q "wasm-bindgen ${WASM_BINDGEN_VERSION}\$"; then
  say "wasm-bindgen-cli ${WASM_BINDGEN_VERSION}: present"
else
  # Without --locked: its lock file names a crate version the registry lacks.
  say "installing wasm-bindgen-cli ${WASM_BINDGEN_VERSION} (about 7 minutes on 2 cores)"
  cargo install wasm-bindgen-cli --version "${WASM_BINDGEN_VERSION}"
fi

# npm ci only when node_modules is missing or older than the lock file.
stamp=node_modules/.package-lock.json
if [[ -f "$stamp" && ! package-lock.json -nt "$stamp" ]] \
  && [[ -x node_modules/.bin/wasm-opt && -d node_modules/playwright-core ]]; then
  say "node_modules: up to date"
else
  say "npm ci"
  npm ci --no-audit --no-fund
fi
if ! wasm-opt --version 2>/dev/null | grep -q "version_132"; then
  echo "[setup] wasm-opt on PATH is not binaryen 132: $(command -v wasm-opt || echo none)" >&2
  exit 1
fi

if [[ -x /usr/bin/chromium ]]; then
  say "chromium: present"
else
  say "installing Debian chromium and chromium-driver"
  SUDO=""
  if [[ "$(id -u)" != 0 ]]; then SUDO=sudo; fi
  $SUDO apt-get update
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends chromium chromium-driver
fi
say "done"

#!/usr/bin/env bash
# Command 2, the one test command (CI runs it through .ci/run): installs what
# is missing, then checks formatting and lints, runs the native tests, runs a
# sharded map on a real one-node Slurm (installed if missing), checks the
# wasm32 builds, builds the release page with Trunk and runs the browser
# tests in headless Debian chromium against it. Exits non-zero on any failure.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh
source scripts/env.sh

step() { printf '\n== %s\n' "$*"; }
t0=$SECONDS

step "cargo fetch"
cargo fetch

step "cargo fmt --check"
cargo fmt --all -- --check

step "cargo clippy (native, all targets)"
cargo clippy --workspace --all-targets -- -D warnings

step "cargo test (native)"
cargo test --workspace

step "cluster: a real one-node Slurm runs a sharded map and its merge (scripts/test-cluster.sh)"
scripts/test-cluster.sh

step "solver builds for wasm32"
cargo build -p solver --target wasm32-unknown-unknown

step "cargo clippy -p app (wasm32)"
cargo clippy -p app --target wasm32-unknown-unknown -- -D warnings

step "trunk build --release"
trunk build --release --offline

step "browser tests (headless chromium)"
node --test --test-concurrency=1 tests/browser/

printf '\n== all checks passed in %d s\n' "$((SECONDS - t0))"

#!/usr/bin/env node
// wasm-vs-native benchmark: builds crates/wasm-bench for wasm32, binds it for
// node with wasm-bindgen, times the same workloads as `gearshock bench`
// (HBM frequency responses H = 1 and H = 7 over Omega 0.1..2 with 400
// nominal points, stability on; one simulate of 300 + 100 periods at
// Omega 0.5; the 200-point bifurcation sweep; a 100 x 4 regime map) in node and natively, and prints medians and the ratios as JSON.
// The wasm is optimized by wasm-opt -O3 as in the page's release build.
// Usage: node scripts/bench-wasm.mjs [repeats]   (run from the repository root,
// with scripts/env.sh sourced so wasm-bindgen is on PATH)
import { execFileSync } from 'node:child_process';
import { writeFileSync } from 'node:fs';
import { createRequire } from 'node:module';
import { performance } from 'node:perf_hooks';

const repeats = Number(process.argv[2] ?? 5);
const run = (cmd, args) => execFileSync(cmd, args, { stdio: ['ignore', 'pipe', 'inherit'] }).toString();

run('cargo', ['build', '--release', '-p', 'wasm-bench', '--target', 'wasm32-unknown-unknown']);
run('wasm-bindgen', ['--target', 'nodejs', '--out-dir', 'target/wasm-bench',
  'target/wasm32-unknown-unknown/release/wasm_bench.wasm']);
// Optimize as the page's build does (Trunk runs binaryen's wasm-opt).
run('wasm-opt', ['-O3', '--enable-bulk-memory', '--enable-nontrapping-float-to-int', '--enable-sign-ext', '--enable-simd',
  'target/wasm-bench/wasm_bench_bg.wasm', '-o', 'target/wasm-bench/wasm_bench_bg.wasm']);
run('cargo', ['build', '--release', '-p', 'cli']);
// The bindings are CommonJS; the repository's package.json says "module".
writeFileSync('target/wasm-bench/package.json', '{ "type": "commonjs" }\n');
const wasm = createRequire(import.meta.url)('../target/wasm-bench/wasm_bench.js');

const median = (xs) => {
  const s = [...xs].sort((a, b) => a - b);
  const n = s.length;
  return n % 2 ? s[(n - 1) / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
};
const time = (f) => {
  f(); // warm-up
  const ms = [];
  for (let i = 0; i < repeats; i++) {
    const t0 = performance.now();
    const r = f();
    ms.push(performance.now() - t0);
    if (r < 0) throw new Error('solver failure in wasm');
  }
  return median(ms);
};

const wasmMs = {
  hbm_h1_ms: time(() => wasm.frf(1, 400, true)),
  hbm_h7_ms: time(() => wasm.frf(7, 400, true)),
  simulate_ms: time(() => wasm.simulate(0.5, 300, 100)),
  bifurcation_200_ms: time(() => wasm.sweep(200)),
  map_100x4_ms: time(() => wasm.map(100, 4)),
};
const native = JSON.parse(run('target/release/gearshock', ['bench', '--repeats', String(repeats)]));
const nativeMs = {
  hbm_h1_ms: native.hbm.h1.median_ms,
  hbm_h7_ms: native.hbm.h7.median_ms,
  simulate_ms: native.simulate.median_ms,
  bifurcation_200_ms: native.bifurcation.median_s * 1000,
  map_100x4_ms: native.map.median_s * 1000,
};
const ratio = Object.fromEntries(Object.keys(wasmMs).map((k) => [k, wasmMs[k] / nativeMs[k]]));
console.log(JSON.stringify({ repeats, node: process.version, wasm_ms: wasmMs, native_ms: nativeMs, wasm_over_native: ratio }, null, 2));

// The Web Worker's loader (index.html and crates/app/src/web.rs start
// workers from it): the worker's WebAssembly is fetched while its
// JavaScript glue (worker.js, from wasm-bindgen) loads, then compiled as
// it streams in, and the worker starts (crates/app/src/web/worker.rs).
const wasm = fetch('./worker_bg.wasm');
importScripts('./worker.js');
wasm_bindgen({ module_or_path: wasm });

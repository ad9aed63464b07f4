//! gearshock's browser explorer as a plain Rust library, testable natively.
//!
//! The page is split like egui/eframe: everything here is pure logic
//! (settings and their link codec, presets, control specs, the worker
//! protocol, the jobs by kind and their runner, the views by kind with the
//! redraw scheduler, the plots, the gear set's scene, the page controller),
//! and one boundary, `web` (web.rs and web/), compiled only for wasm32,
//! touches `wasm_bindgen` and `web_sys`. Two binaries start it: `app` on the
//! page's main thread and `worker` in each Web Worker. ARCHITECTURE.md maps
//! the modules and their invariants.
//!
//! Architecture invariant: heavy work (steady states, sweeps, the
//! harmonic-balance continuation) runs only in the workers ([`worker`] and
//! its `jobs`); the main thread builds the small model for validation
//! and natural frequencies, draws, and never blocks for long.

#![warn(unreachable_pub)]

pub mod claims;
pub mod controller;
pub mod controls;
pub mod family;
pub mod gearset;
pub mod link;
pub mod page;
pub mod panels;
pub mod plots;
pub mod presets;
pub mod protocol;
pub mod scene;
pub mod settings;
pub mod store;
pub mod tour;
pub mod views;
pub mod words;
pub mod worker;
/// The worker's job runner under its earlier name.
pub use worker as worker_core;

#[cfg(target_arch = "wasm32")]
pub mod web;

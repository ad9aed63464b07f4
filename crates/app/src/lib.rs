//! gearshock's browser explorer as a plain Rust library, testable natively.
//!
//! The page is split like egui/eframe: everything here is pure logic, in
//! rooms that show the page/worker split: the page side ([`page`], the
//! page core with the redraw scheduler; [`controller`]; [`store`], one
//! computation's results; [`views`]; [`plots`]), the worker side
//! ([`worker`] and its jobs), what both speak ([`protocol`]), and the
//! state, its link codec and its words at the top. One boundary, `web`
//! (web.rs and web/), compiled only for wasm32, touches `wasm_bindgen` and
//! `web_sys`: glue that hands events to the page core and paints. Two binaries start it: `app` on the
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
pub mod failure;
pub mod family_spec;
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
pub mod story;
pub mod tour;
pub mod validity;
pub mod views;
pub mod words;
pub mod worker;

#[cfg(target_arch = "wasm32")]
pub mod web;

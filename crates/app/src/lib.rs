//! gearshock's page as a plain Rust library, testable natively.
//!
//! The page is split like egui/eframe: everything here is pure logic, the
//! page side of the page/worker split ([`page`], the page core with the
//! redraw scheduler; [`controller`]; [`store`], one computation's results;
//! the tour, the paper's claims, the gear set's picture), over two
//! platform-free crates: `figures` (the state, its link codec and words,
//! the story, the messages, the views and plots, shared with the command
//! line) and `worker` (the Web Worker's runner and jobs). One boundary,
//! `web` (web.rs and web/), compiled only for wasm32, touches
//! `wasm_bindgen` and `web_sys`: glue that hands events to the page core
//! and paints. Two binaries start it: `app` on the page's main thread and
//! `worker` in each Web Worker. ARCHITECTURE.md maps the crates and their
//! invariants.
//!
//! Architecture invariant: heavy work (steady states, sweeps, the
//! harmonic-balance continuation) runs only in the workers (the `worker`
//! crate's jobs); the main thread builds the small model for validation
//! and natural frequencies, draws, and never blocks for long.

#![warn(unreachable_pub)]

pub mod claims;
pub mod controller;
pub mod gearset;
pub mod page;
pub mod scene;
pub mod store;
pub mod tour;
pub mod validity;

#[cfg(target_arch = "wasm32")]
pub mod web;

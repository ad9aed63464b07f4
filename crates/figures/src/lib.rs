//! What gearshock's page and its command line share, as plain Rust with no
//! platform code: the settings and their link codec, the presets (the
//! paper's figures), the story of a steady state (its one classification
//! and its sentences), the messages between the page and its workers with
//! the result types they carry, the view models, and the plots drawn on any
//! plotters backend (the page's canvases, the SVG of the exports and of
//! `gearshock figure`).
//!
//! Architecture invariant: this crate imports only the solver and
//! platform-free libraries (serde, plotters' drawing core, glam); it knows
//! nothing of the browser, the page's core or the worker's runner, so the
//! command line builds on it without the page.

#![warn(unreachable_pub)]

pub mod controls;
pub mod failure;
pub mod family_spec;
pub mod link;
pub mod panels;
pub mod plots;
pub mod presets;
pub mod protocol;
pub mod settings;
pub mod speed;
pub mod story;
pub mod te_fit;
pub mod views;
pub mod words;

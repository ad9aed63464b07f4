//! Helpers shared by gearshock's integration tests.
//!
//! - [`cli`]: runs the `gearshock` binary and reads what it printed and
//!   wrote (the CLI's tests, split by subcommand, all use it).
//! - [`modgraph`]: a crate's module import graph read from its source, and
//!   a cycle finder (the solver's and the app's architecture tests).
//! - [`models`]: a model from key assignments and a strict steady-state
//!   run's options (the solver's tests).
//!
//! Its own test, `tests/architecture_doc.rs`, checks the whole of
//! ARCHITECTURE.md against the tree: every name it quotes exists, every
//! room of its code maps, and every invariant names its test.

// Test helpers fail by panicking: that is how a test reports.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

pub mod cli;
pub mod models;
pub mod modgraph;

//! Helpers shared by gearshock's integration tests.
//!
//! - [`cli`]: runs the `gearshock` binary and reads what it printed and
//!   wrote (the CLI's tests, split by subcommand, all use it).

// Test helpers fail by panicking: that is how a test reports.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

pub mod cli;

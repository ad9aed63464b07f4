//! How the planets share the load in a steady state, as the worker sends
//! it with the selected Omega's result (`solver::sharing`'s rows).

use serde::{Deserialize, Serialize};

/// How the planets of one mesh kind share the load in a steady state
/// (`solver::sharing`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct KindSharing {
    /// The mesh kind's key (`s1a`, `s2b`, `ab`, `rb`).
    pub kind: String,
    /// Largest mesh force of each planet's mesh (N), by planet.
    pub peak_force_n: Vec<f64>,
    /// Largest peak over the mean peak (`None`: the kind carries no load).
    pub factor: Option<f64>,
}

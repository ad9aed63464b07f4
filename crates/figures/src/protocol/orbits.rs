//! One point of a shooting branch as the page receives it: the orbit's
//! Poincaré samples on every mesh (one per mesh period of its period),
//! its stability and the bifurcation found before it.

use super::BranchBif;
use serde::{Deserialize, Serialize};

/// One periodic orbit on a shooting branch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OrbitSample {
    /// Dimensionless frequency.
    pub omega: f64,
    /// Period in mesh periods.
    pub period: u32,
    /// Floquet stability, `None` if the multipliers failed.
    pub stable: Option<bool>,
    /// A bifurcation located between the previous point and this one.
    pub bifurcation: Option<BranchBif>,
    /// The branch (0 for the first, one more for each branch switched to or
    /// started): lines join points of one branch only.
    pub piece: u32,
    /// Every mesh's Poincaré samples of x = delta - e (µm), `period` each,
    /// in the model's mesh order.
    pub x_um: Vec<Vec<f64>>,
}

//! The mesh force by order, as the worker sends it with the selected
//! Omega's result (`solver::orders`): the plotted mesh's force spectrum in
//! orders of the mesh frequency with its labelled peaks, and the force
//! summed over the planets' meshes of its kind.

use serde::{Deserialize, Serialize};

/// One labelled line of an order spectrum.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OrderPeak {
    /// The order (mesh orders).
    pub order: f64,
    /// The order in words ("2×", "1/2×", "0.37×").
    pub label: String,
    /// A whole mesh order.
    pub whole: bool,
    /// Its amplitude (N).
    pub amplitude_n: f64,
}

/// The force summed over the planets' meshes of one kind.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlanetSumOrders {
    /// The mesh kind's key (`s1a`, `s2b`, `ab`, `rb`).
    pub kind: String,
    /// How many planets' meshes are summed.
    pub planets: usize,
    /// The sum's amplitude at each order of [`ForceByOrder::order`] (N).
    pub amplitude_n: Vec<f64>,
    /// Its labelled peaks.
    pub peaks: Vec<OrderPeak>,
    /// The share of the in-phase sum the phases leave at whole orders 1, 2, ...
    pub phasing: Vec<f64>,
    /// The whole orders the phasing cancels.
    pub cancelled: Vec<u32>,
}

/// The plotted mesh's force by order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ForceByOrder {
    /// Mesh periods recorded (bin k is order k / record_periods).
    pub record_periods: u32,
    /// The orders of the lines, from 0 (the mean).
    pub order: Vec<f64>,
    /// The mesh force's amplitude at each order (N; the mean at order 0).
    pub amplitude_n: Vec<f64>,
    /// Its labelled peaks, by rising order.
    pub peaks: Vec<OrderPeak>,
    /// The sum over the planets of the mesh's kind (none for the gear pair).
    pub sum: Option<PlanetSumOrders>,
}

impl ForceByOrder {
    /// The solver's spectrum in the page's terms (mesh kinds by key).
    pub fn of(f: &solver::orders::ForceOrders) -> Self {
        let peaks = |p: &[solver::orders::OrderPeak]| {
            p.iter()
                .map(|p| OrderPeak {
                    order: p.order,
                    label: p.label.clone(),
                    whole: p.whole,
                    amplitude_n: p.amplitude_n,
                })
                .collect()
        };
        ForceByOrder {
            record_periods: f.record_periods,
            order: f.order.clone(),
            amplitude_n: f.amplitude_n.clone(),
            peaks: peaks(&f.peaks),
            sum: f.planets.as_ref().map(|s| PlanetSumOrders {
                kind: s.kind.key().to_string(),
                planets: s.meshes.len(),
                amplitude_n: s.amplitude_n.clone(),
                peaks: peaks(&s.peaks),
                phasing: s.phasing.clone(),
                cancelled: s.cancelled.clone(),
            }),
        }
    }
}

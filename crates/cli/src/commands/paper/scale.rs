//! The frequency scale: gearshock's natural frequencies, the bands of
//! parametric instability, the factor that matches the paper's Omega on
//! the first mode, and the input speed per unit of Omega.

use super::data::{f, items, Spans};
use super::runs::Runs;
use crate::failure::Failure;
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// `gearshock modes`.
pub const MODES: &str = "gearshock modes";
/// The default parameters.
pub const PARAMS: &str = "gearshock params";
/// The modes with the ring's support radius read as printed.
pub const MODES_PRINTED: &str = "gearshock modes --set ring_support_radius_mm=15.79";
/// The bands of parametric instability.
pub const INSTABILITY: &str = "gearshock instability --omega-from 0.1 --omega-to 2 --points 381";
/// The paper's Omega the document converts (its resonances, the Omegas of
/// Figs. 5-7 and 9-11, its advised limit).
pub const PAPER_OMEGAS: [f64; 7] = [0.4, 0.5, 0.8, 0.84, 1.2, 1.4, 1.97];
/// The paper's resonance that the matched scale puts on gearshock's first
/// natural frequency.
pub const PAPER_FIRST: f64 = 0.4;
/// The paper's frequency sections on its own scale (section 3.2: Figs. 5,
/// 6 and 7 stand for the low, medium and high sections; its high section
/// is Omega 1.2-2), each up to its upper end.
pub const PAPER_SECTIONS: [(&str, f64, f64); 3] =
    [("low", 0.0, 0.5), ("medium", 0.5, 1.2), ("high", 1.2, 2.0)];

/// gearshock's frequencies and the two scales.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Scale {
    /// The reference frequency of Omega (rad/s).
    pub omega_ref_rad_s: f64,
    /// The rotational modes' Omega (every planet alike), distinct at 3 decimals.
    pub rotational: Vec<f64>,
    /// The planet modes' Omega (suns, carrier and ring still).
    pub planet: Vec<f64>,
    /// The rotational modes with the ring's support radius as printed.
    pub printed_rotational: Vec<f64>,
    /// The bands of parametric instability (every tooth pair engaged).
    pub bands: Spans,
    /// gearshock's first natural frequency (Omega).
    pub first_mode: f64,
    /// The matched scale: gearshock's Omega per unit of the paper's.
    pub factor: f64,
    /// The small sun's input speed per unit of Omega (rpm).
    pub rpm_per_omega: f64,
}

impl Scale {
    /// The paper's `w` on gearshock's scale, matched on the first mode, to
    /// the 3 decimals the commands take.
    pub fn matched(&self, w: f64) -> f64 {
        (w * self.factor * 1000.0).round() / 1000.0
    }

    /// The band of parametric instability holding `w`, if one does.
    pub fn band_of(&self, w: f64) -> Option<(f64, f64)> {
        self.bands
            .iter()
            .copied()
            .find(|&(a, b)| (a - 1e-9..=b + 1e-9).contains(&w))
    }
}

/// The command lines the scale reads.
pub fn lines() -> Vec<String> {
    vec![
        MODES.into(),
        PARAMS.into(),
        MODES_PRINTED.into(),
        INSTABILITY.into(),
        super::orbits::rpm_line(),
    ]
}

/// Distinct Omegas of one kind of mode, at 3 decimals.
fn natural(v: &Value, kind: &str) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::new();
    for m in items(v, "modes") {
        let w = (f(&m["omega"]) * 1000.0).round() / 1000.0;
        if m["kind"] == kind && !out.contains(&w) {
            out.push(w);
        }
    }
    out
}

/// Reads the scale off the runs.
pub fn compute(runs: &Runs) -> Result<Scale, Failure> {
    let base = runs.get(MODES)?;
    let printed = runs.get(MODES_PRINTED)?;
    let bands = runs.get(INSTABILITY)?;
    let first_mode = items(&base, "modes")
        .iter()
        .filter(|m| m["kind"] == "rotational")
        .map(|m| f(&m["omega"]))
        .fold(f64::INFINITY, f64::min);
    let unstable = super::data::spans(items(&bands, "points"), |p| p["unstable"] == true);
    let one = runs.get(&super::orbits::rpm_line())?;
    Ok(Scale {
        omega_ref_rad_s: f(&base["omega_ref_rad_s"]),
        rotational: natural(&base, "rotational"),
        planet: natural(&base, "planet"),
        printed_rotational: natural(&printed, "rotational"),
        bands: unstable,
        first_mode,
        factor: first_mode / PAPER_FIRST,
        rpm_per_omega: f(&one["input_speed_rpm"]) / f(&one["omega"]),
    })
}

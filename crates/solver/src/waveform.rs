//! The mesh stiffness waveform and its Fourier series, and the contact ratio
//! of standard spur teeth.
//!
//! Every waveform is written `k(theta) = k_m (1 + v w(theta))` with
//! `theta = omega t + gamma` the mesh phase, `k_m` the *time mean* of the
//! stiffness (so the static deflection, the modes and the natural
//! frequencies do not depend on the waveform) and `w` a zero-mean shape
//! whose peak-to-peak is 2: `v` is half the peak-to-peak stiffness relative
//! to the mean. The solver sees only the series
//! `w(theta) = sum_n a_n cos(n theta)` (every shape is even in `theta`), cut
//! at a number of harmonics the user sets.
//!
//! - Cosine (the seed's): `w = cos theta`, `a_1 = 1`, nothing else.
//! - Rectangular: double tooth contact for the fraction `d = eps - floor(eps)`
//!   of each mesh period (`eps` the contact ratio), centred on `theta = 0`.
//!   Levels `w = 2 (1 - d)` in double and `-2 d` in single contact, so
//!   `a_n = 4 sin(n pi d) / (n pi)`.
//! - Trapezoid: the rectangle with each switch spread over a linear ramp of
//!   width `r` mesh periods centred on the switch (the rectangle convolved
//!   with a box of width `r`): `a_n = 4 sin(n pi d) / (n pi) * sin(n pi r) / (n pi r)`,
//!   with `r <= min(d, 1 - d)` so that both flats remain.
//!
//! With `v = 0.3` and `eps = 1.6` the rectangle switches between
//! `k_m (1 - 0.36)` and `k_m (1 + 0.24)`, a double- to single-contact
//! stiffness ratio of 1.94.

use crate::error::{Result, SolverError};
use std::f64::consts::PI;

/// The shape of a mesh's stiffness over one mesh period.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Wave {
    /// `k_m (1 + v cos theta)`: the seed's single harmonic (the default).
    Cosine,
    /// Single and double tooth contact, switching at once.
    Rectangular,
    /// Single and double tooth contact joined by linear ramps.
    Trapezoid,
}

impl Wave {
    /// The names used in keys.
    pub const NAMES: [&'static str; 3] = ["cosine", "rectangular", "trapezoid"];

    /// The name used in keys.
    pub fn name(self) -> &'static str {
        match self {
            Wave::Cosine => "cosine",
            Wave::Rectangular => "rectangular",
            Wave::Trapezoid => "trapezoid",
        }
    }

    /// Parses a name written by [`Wave::name`] (anything else is the cosine).
    pub fn from_name(name: &str) -> Self {
        match name {
            "rectangular" => Wave::Rectangular,
            "trapezoid" => Wave::Trapezoid,
            _ => Wave::Cosine,
        }
    }
}

/// The contact ratio of two external spur gears of full-depth standard
/// teeth (addendum one module, no profile shift): the length of the path of
/// contact over the base pitch.
pub fn contact_ratio_external(z1: u32, z2: u32, module_mm: f64, pressure_angle_deg: f64) -> f64 {
    let (sa, ca) = pressure_angle_deg.to_radians().sin_cos();
    let r = |z: u32| module_mm * f64::from(z) / 2.0;
    let path = |z: u32| ((r(z) + module_mm).powi(2) - (r(z) * ca).powi(2)).sqrt();
    (path(z1) + path(z2) - (r(z1) + r(z2)) * sa) / (PI * module_mm * ca)
}

/// The contact ratio of a planet (`z_planet` teeth) inside a ring
/// (`z_ring`), full-depth standard teeth (the ring's tips one module inside
/// its pitch circle).
pub fn contact_ratio_internal(
    z_planet: u32,
    z_ring: u32,
    module_mm: f64,
    pressure_angle_deg: f64,
) -> f64 {
    let (sa, ca) = pressure_angle_deg.to_radians().sin_cos();
    let (rp, rr) = (
        module_mm * f64::from(z_planet) / 2.0,
        module_mm * f64::from(z_ring) / 2.0,
    );
    let planet = ((rp + module_mm).powi(2) - (rp * ca).powi(2)).sqrt();
    let ring = ((rr - module_mm).powi(2) - (rr * ca).powi(2))
        .max(0.0)
        .sqrt();
    (planet - ring + (rr - rp) * sa) / (PI * module_mm * ca)
}

/// The contact ratio of a mesh: [`contact_ratio_internal`] (`z1` the
/// planet, `z2` the ring) if `internal`, else [`contact_ratio_external`].
pub fn contact_ratio(z1: u32, z2: u32, internal: bool, module_mm: f64, alpha_deg: f64) -> f64 {
    if internal {
        contact_ratio_internal(z1, z2, module_mm, alpha_deg)
    } else {
        contact_ratio_external(z1, z2, module_mm, alpha_deg)
    }
}

/// Smallest and largest contact ratio a waveform accepts.
pub const CONTACT_RATIO_RANGE: (f64, f64) = (1.0, 2.95);

/// The relative cosine coefficients `v a_1, v a_2, ...` of a stiffness
/// waveform, `harmonics` of them (the cosine has one whatever `harmonics`).
///
/// `contact_ratio` and `ramp` are read by the rectangle and the trapezoid.
/// Refused: a contact ratio outside [`CONTACT_RATIO_RANGE`], a ramp wider
/// than either flat, and a truncated series whose stiffness is not positive
/// over the whole period (`what` names the mesh kind in the message).
pub fn stiffness_series(
    what: &str,
    wave: Wave,
    variation: f64,
    contact_ratio: f64,
    ramp: f64,
    harmonics: usize,
) -> Result<Vec<f64>> {
    if wave == Wave::Cosine {
        return Ok(vec![variation]);
    }
    let (lo, hi) = CONTACT_RATIO_RANGE;
    if !(contact_ratio.is_finite() && (lo..=hi).contains(&contact_ratio)) {
        return Err(SolverError::Geometry {
            message: format!(
                "the {what} meshes' contact ratio is {contact_ratio:.3}; a {} stiffness needs \
                 {lo} ..= {hi} (give it as a key)",
                wave.name()
            ),
        });
    }
    let d = contact_ratio - contact_ratio.floor();
    let ramp = if wave == Wave::Trapezoid { ramp } else { 0.0 };
    if ramp > d.min(1.0 - d) + 1e-12 {
        return Err(SolverError::Geometry {
            message: format!(
                "the {what} meshes' stiffness ramp {ramp} is wider than their shorter flat: \
                 with contact ratio {contact_ratio:.3} it may be at most {:.3} of a mesh period",
                d.min(1.0 - d)
            ),
        });
    }
    let series: Vec<f64> = (1..=harmonics)
        .map(|n| variation * rectangle_coefficient(n, d) * box_factor(n, ramp))
        .collect();
    // The truncated series overshoots at the switches (Gibbs): it must stay
    // a spring everywhere.
    let samples = 64 * harmonics.max(1);
    let lowest = (0..samples)
        .map(|i| {
            let t = 2.0 * PI * i as f64 / samples as f64;
            1.0 + series
                .iter()
                .enumerate()
                .map(|(n, a)| a * ((n + 1) as f64 * t).cos())
                .sum::<f64>()
        })
        .fold(f64::INFINITY, f64::min);
    if lowest <= 0.0 {
        return Err(SolverError::Geometry {
            message: format!(
                "the {what} meshes' {} stiffness with variation {variation} and {harmonics} \
                 harmonics falls to {lowest:.3} times its mean: use a smaller variation",
                wave.name()
            ),
        });
    }
    Ok(series)
}

/// `a_n = 4 sin(n pi d) / (n pi)`: the rectangle of duty `d` and peak-to-peak 2.
fn rectangle_coefficient(n: usize, d: f64) -> f64 {
    let x = n as f64 * PI;
    4.0 * (x * d).sin() / x
}

/// `sin(n pi r) / (n pi r)`: a box of width `r` periods (1 for `r = 0`).
fn box_factor(n: usize, r: f64) -> f64 {
    let x = n as f64 * PI * r;
    if x == 0.0 {
        1.0
    } else {
        x.sin() / x
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rectangle's coefficients are the integrals of its levels.
    #[test]
    fn rectangle_coefficients_are_the_integrals_of_its_levels() {
        let (d, v) = (0.6, 0.3);
        let a = stiffness_series("s1a", Wave::Rectangular, v, 1.6, 0.0, 6).unwrap();
        // (1/pi) int_{-pi}^{pi} w cos(n t) dt, by the midpoint rule on w itself.
        let m = 200_000;
        for (n, an) in a.iter().enumerate() {
            let n = (n + 1) as f64;
            let s: f64 = (0..m)
                .map(|i| {
                    let t = -PI + 2.0 * PI * (i as f64 + 0.5) / m as f64;
                    let w = if t.abs() < PI * d {
                        2.0 * (1.0 - d)
                    } else {
                        -2.0 * d
                    };
                    v * w * (n * t).cos()
                })
                .sum::<f64>()
                * 2.0
                / m as f64;
            assert!((an - s).abs() < 1e-4, "n = {n}: {an} vs {s}");
        }
    }

    /// The default pair (30 and 45 teeth, module 4, 20 degrees) has a
    /// contact ratio of 1.69 by the hand calculation below.
    #[test]
    fn the_default_pairs_contact_ratio_is_the_hand_calculation() {
        // Path of contact: sqrt(64^2 - 56.38^2) + sqrt(94^2 - 84.57^2) - 150 sin 20 = 20.01 mm,
        // base pitch 4 pi cos 20 = 11.81 mm.
        let e = contact_ratio_external(30, 45, 4.0, 20.0);
        assert!((e - 1.695).abs() < 2e-3, "{e}");
        let i = contact_ratio_internal(18, 84, 4.0, 20.0);
        assert!(i > e && i < 2.2, "{i}");
        // The page's automatic value is that of the model's teeth.
        use crate::params::{ModelKind, ModelParams};
        let pair = ModelParams::defaults(ModelKind::GearPair);
        let auto = pair.auto_contact_ratio("pair").unwrap();
        assert!((auto - 1.695).abs() < 2e-3, "{auto}");
        assert_eq!(pair.auto_contact_ratio("s1a"), None);
        // The compound set's ring mesh: the long planet has (84 - 48) / 2 = 18 teeth.
        let set = ModelParams::defaults(ModelKind::Ravigneaux);
        let ring = set.auto_contact_ratio("rb").unwrap();
        assert!((ring - contact_ratio_internal(18, 84, 4.0, 20.0)).abs() < 1e-12);
    }
}

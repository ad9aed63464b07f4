//! Parametric instability of the fully engaged gear set: the Floquet
//! multipliers, over Omega, of the linear time-periodic system in which
//! every tooth pair is in contact.
//!
//! Beyond the dead zone the force law is linear (`k_j(t) (x - b)`), so any
//! motion large against the backlash obeys `M q'' + C q' + K(t) q = f(t)`
//! with the mesh stiffnesses `k_j(t) = k_m (1 + v cos(Omega t + gamma_j))`.
//! Where a Floquet multiplier of its homogeneous part lies outside the unit
//! circle (spectral radius `rho > 1`), such motion grows by `rho` per mesh
//! period without bound: a parametric instability (Lin & Parker's for
//! planetary gears). A smaller motion may still stay on a bounded attractor
//! (the dead zone detunes it), which is why an upward sweep that warmed up on
//! a large-amplitude branch can be carried off there while a run from the
//! static state stays bounded; such runs stop with
//! [`crate::SolverError::Diverged`].
//!
//! The multipliers come from the harmonic-balance stability code
//! ([`crate::hbm::stability::floquet_engaged`]): an RK4 monodromy in scaled
//! modal coordinates with the rigid-body mode removed (its multiplier is 1
//! for any Omega), the symmetric set and its planet block separately.

use crate::error::{Result, SolverError};
use crate::hbm::stability::floquet_engaged;
use crate::hbm::{Assembly, HbmModel, Method};
use crate::steady::Model;

/// The engaged system's stability at one Omega.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EngagedStability {
    /// Dimensionless mesh frequency.
    pub omega: f64,
    /// Largest modulus of the Floquet multipliers per mesh period.
    pub spectral_radius: f64,
}

impl EngagedStability {
    /// `ln rho`: the growth (positive) or decay of large motion per mesh period.
    pub fn growth_per_period(&self) -> f64 {
        self.spectral_radius.ln()
    }

    /// Whether large motion grows without bound here.
    pub fn unstable(&self) -> bool {
        self.spectral_radius > 1.0
    }
}

/// A model prepared for [`Parametric::at`].
#[derive(Debug, Clone)]
pub struct Parametric {
    asm: Assembly,
}

impl Parametric {
    /// Prepares the engaged system of `model` (scaled modal coordinates,
    /// rigid mode removed, symmetric reduction where the phasing allows it).
    pub fn new(model: &Model) -> Result<Self> {
        let hbm = HbmModel::from_system(&model.system, true)?;
        Ok(Parametric {
            asm: Assembly::new(hbm, 1, Method::Exact, 64),
        })
    }

    /// The engaged system's Floquet spectral radius at `omega` (0.01 ..= 20).
    pub fn at(&self, omega: f64) -> Result<EngagedStability> {
        if !(omega.is_finite() && (0.01..=20.0).contains(&omega)) {
            return SolverError::bad_option("omega", omega, "0.01 ..= 20");
        }
        let f = floquet_engaged(&self.asm, omega).ok_or_else(|| SolverError::Singular {
            what: format!(
                "Floquet multipliers of the engaged system at Omega = {omega}: \
                 the eigenvalue iteration did not converge"
            ),
        })?;
        Ok(EngagedStability {
            omega,
            spectral_radius: f.spectral_radius(),
        })
    }
}

impl Parametric {
    /// The Omega intervals of `range` where the engaged system is unstable,
    /// from `samples` (at least 2) equally spaced Omegas (a band narrower
    /// than the spacing can slip between them); see [`unstable_bands`].
    pub fn unstable_bands(&self, range: (f64, f64), samples: u32) -> Result<Vec<(f64, f64)>> {
        let n = samples.max(2);
        let mut points = Vec::with_capacity(n as usize);
        for i in 0..n {
            let omega = range.0 + (range.1 - range.0) * f64::from(i) / f64::from(n - 1);
            let s = self.at(omega.max(0.01))?;
            points.push((omega, s.growth_per_period()));
        }
        Ok(unstable_bands(&points, range.1))
    }
}

/// The Omega intervals where the growth per period `ln rho` of `points`
/// (`(omega, ln rho)`, ascending in Omega) is positive, each edge
/// interpolated linearly in `ln rho` between the samples that straddle it;
/// a band still open at the last sample ends at `end`.
pub fn unstable_bands(points: &[(f64, f64)], end: f64) -> Vec<(f64, f64)> {
    let edge = |(o0, g0): (f64, f64), (o1, g1): (f64, f64)| o0 + (o1 - o0) * g0 / (g0 - g1);
    let mut bands = Vec::new();
    let mut start = points.first().filter(|g| g.1 > 0.0).map(|g| g.0);
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        match (a.1 > 0.0, b.1 > 0.0) {
            (false, true) => start = Some(edge(a, b)),
            (true, false) => {
                if let Some(s0) = start.take() {
                    bands.push((s0, edge(a, b)));
                }
            }
            _ => {}
        }
    }
    if let Some(s0) = start {
        bands.push((s0, end));
    }
    bands
}

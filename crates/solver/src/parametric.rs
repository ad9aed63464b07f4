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

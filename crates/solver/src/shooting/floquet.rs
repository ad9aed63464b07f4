//! Floquet multipliers of a shooting orbit and how its stability is lost.
//!
//! The multipliers are the eigenvalues of the reduced monodromy `dP^n/dz`
//! (nalgebra's real Schur form). The orbit is stable when all lie inside
//! the unit circle; the one of largest modulus says how stability is lost
//! where it leaves: through +1 a fold (or a branch point), through -1 a
//! period doubling, as a complex pair a Neimark–Sacker bifurcation.

use crate::bifurcation::Bifurcation;
use nalgebra::{Complex, DMatrix, DVector};

/// How far outside the unit circle a multiplier may lie and the orbit still
/// count as stable: the monodromy's own integration error.
pub const STABILITY_MARGIN: f64 = 1e-6;

/// The multipliers of one orbit.
#[derive(Debug, Clone, PartialEq)]
pub struct Multipliers {
    /// All multipliers, largest modulus first.
    pub values: Vec<Complex<f64>>,
}

impl Multipliers {
    /// The eigenvalues of `monodromy`, or `None` if the Schur form fails.
    pub fn of(monodromy: &DMatrix<f64>) -> Option<Self> {
        let mut values = crate::dense::eigenvalues_with(monodromy, 1e-14, 10_000)?;
        values.sort_by(|a, b| b.norm().total_cmp(&a.norm()));
        Some(Multipliers { values })
    }

    /// The largest modulus (the spectral radius).
    pub fn max_modulus(&self) -> f64 {
        self.values.first().map_or(0.0, |v| v.norm())
    }

    /// Stable: every multiplier inside the unit circle (within [`STABILITY_MARGIN`]).
    pub fn is_stable(&self) -> bool {
        self.max_modulus() <= 1.0 + STABILITY_MARGIN
    }

    /// The critical multiplier: the largest in modulus.
    pub fn critical(&self) -> Option<Complex<f64>> {
        self.values.first().copied()
    }

    /// How stability is lost (or would be) through the critical multiplier.
    pub fn critical_kind(&self) -> Option<Bifurcation> {
        self.critical().map(classify_multiplier)
    }

    /// The largest real multiplier below zero, if any: the one that crosses
    /// -1 at a period doubling.
    pub fn most_negative_real(&self) -> Option<f64> {
        self.real_ones().filter(|v| *v < 0.0).min_by(f64::total_cmp)
    }

    /// The largest real multiplier above zero, if any: the one that crosses
    /// +1 at a fold.
    pub fn largest_positive_real(&self) -> Option<f64> {
        self.real_ones().filter(|v| *v > 0.0).max_by(f64::total_cmp)
    }

    /// The largest modulus among the complex pairs, if any.
    pub fn largest_complex_modulus(&self) -> Option<f64> {
        self.values
            .iter()
            .filter(|v| !is_real(**v))
            .map(|v| v.norm())
            .max_by(f64::total_cmp)
    }

    fn real_ones(&self) -> impl Iterator<Item = f64> + '_ {
        self.values.iter().filter(|v| is_real(**v)).map(|v| v.re)
    }
}

/// A multiplier counts as real when its imaginary part is below 1e-9 of its modulus.
fn is_real(v: Complex<f64>) -> bool {
    v.im.abs() <= 1e-9 * v.norm().max(1e-300)
}

/// The bifurcation a multiplier on the unit circle stands for: +1 a fold,
/// -1 a period doubling, a complex pair a Neimark–Sacker point.
pub fn classify_multiplier(v: Complex<f64>) -> Bifurcation {
    if !is_real(v) {
        Bifurcation::NeimarkSacker
    } else if v.re < 0.0 {
        Bifurcation::PeriodDoubling
    } else {
        Bifurcation::Fold
    }
}

/// A unit vector `e` with `monodromy e = mu e` for a real multiplier `mu`:
/// the right singular vector of `monodromy - mu I` with the smallest
/// singular value.
pub(crate) fn real_eigenvector(monodromy: &DMatrix<f64>, mu: f64) -> Option<DVector<f64>> {
    let m = monodromy.nrows();
    let a = monodromy - DMatrix::identity(m, m) * mu;
    let svd = a.try_svd(false, true, 1e-14, 10_000)?;
    let v_t = svd.v_t?;
    let (k, _) = svd
        .singular_values
        .iter()
        .enumerate()
        .min_by(|a, b| a.1.total_cmp(b.1))?;
    let e: DVector<f64> = v_t.row(k).transpose();
    let norm = e.norm();
    (norm > 0.0).then(|| e / norm)
}

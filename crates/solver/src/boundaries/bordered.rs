//! What the augmented systems share: one evaluation's result ([`Eval`])
//! and the bordered matrix `[A b; c^T 0]` whose last unknown vanishes
//! where `A` is singular (the fold's and the period doubling's test).

use crate::error::{Result, SolverError};
use nalgebra::{DMatrix, DVector};

/// One evaluation of an augmented system.
#[derive(Debug, Clone)]
pub(crate) struct Eval {
    /// The residual, `n - 1` entries.
    pub(crate) res: DVector<f64>,
    /// Its Jacobian, `(n - 1) x n`.
    pub(crate) jac: DMatrix<f64>,
    /// A vector in `(Omega, p)` pointing to the side where the change the
    /// curve marks has not happened (the branch still exists, the contact
    /// has not begun).
    pub(crate) side: (f64, f64),
    /// The cusp test (folds only; zero otherwise).
    pub(crate) cusp: f64,
    /// Scale of the orbit (largest coefficient, um).
    pub(crate) scale: f64,
    /// Period doublings only: whether every other Floquet multiplier is
    /// inside the unit circle (the doubling happens on a stable orbit).
    pub(crate) others_stable: Option<bool>,
}

/// The bordered matrix `[J b; c^T 0]`.
pub(crate) fn bordered(jx: &DMatrix<f64>, b: &DVector<f64>, c: &DVector<f64>) -> DMatrix<f64> {
    let nx = jx.nrows();
    let mut a = DMatrix::zeros(nx + 1, nx + 1);
    a.view_mut((0, 0), (nx, nx)).copy_from(&jx.columns(0, nx));
    for i in 0..nx {
        a[(i, nx)] = b[i];
        a[(nx, i)] = c[i];
    }
    a
}

/// Solves `[A b; c^T 0] [v; g] = [0; 1]`: `(g, v)`.
pub(crate) fn bordered_solve(
    a: &DMatrix<f64>,
    b: &DVector<f64>,
    c: &DVector<f64>,
    omega: f64,
) -> Result<(f64, DVector<f64>)> {
    let n = a.nrows();
    let mut e = DVector::zeros(n + 1);
    e[n] = 1.0;
    let sol = bordered(a, b, c)
        .lu()
        .solve(&e)
        .ok_or_else(|| SolverError::Singular {
            what: format!("bordered matrix at Omega = {omega}"),
        })?;
    Ok((sol[n], sol.rows(0, n).into_owned()))
}
